#include "simplify/handover_slot.h"

namespace crowdbake {
namespace {

// note: about as long as the loop takes between two posts on a hero mesh (a few tens of
// microseconds); a wait longer than that means the other side is not running, and sleeping
// then gives its core back.
constexpr unsigned kSpins = 2048;

void pause() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#elif defined(__aarch64__)
  asm volatile("yield");
#endif
}

}  // namespace

template <class Ready>
void HandoverSlot::wait_until(Ready ready) {
  for (unsigned spins = 0; spins < kSpins; ++spins) {
    if (ready()) return;
    pause();
  }
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait(lock, ready);
}

// note: the lock between the change and the notification means a side that found the state
// unchanged under the lock is already waiting when the notification comes.
void HandoverSlot::set(State s) {
  state_.store(s, std::memory_order_release);
  { std::lock_guard<std::mutex> lock(mutex_); }
  changed_.notify_all();
}

void HandoverSlot::post() { set(kPosted); }

bool HandoverSlot::take_back() {
  int posted = kPosted;
  return state_.compare_exchange_strong(posted, kEmpty, std::memory_order_acq_rel);
}

void HandoverSlot::wait_done() {
  wait_until([this] { return state_.load(std::memory_order_acquire) == kDone; });
  state_.store(kEmpty, std::memory_order_relaxed);
}

bool HandoverSlot::wait_job() {
  for (;;) {
    wait_until([this] {
      return stopping_.load(std::memory_order_relaxed) ||
             state_.load(std::memory_order_relaxed) == kPosted;
    });
    if (stopping_.load(std::memory_order_relaxed)) return false;
    int posted = kPosted;
    // note: failing means the loop took the job back first.
    if (state_.compare_exchange_strong(posted, kTaken, std::memory_order_acq_rel)) return true;
  }
}

void HandoverSlot::finish() { set(kDone); }

void HandoverSlot::stop() {
  stopping_.store(true, std::memory_order_relaxed);
  { std::lock_guard<std::mutex> lock(mutex_); }
  changed_.notify_all();
}

}  // namespace crowdbake
