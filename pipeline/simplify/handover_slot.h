// One job at a time from the collapse loop to its lookahead thread, which the loop takes back
// when the thread has not started it yet.
//
// note: the two sides spin briefly and then sleep. Spinning alone (with a yield every few
// thousand turns) is as fast on an idle machine, but on cores other processes keep busy the
// spinning side held a core the sleeping one needed, and the loop waited for a lookahead
// thread that was not running: the 1M-triangle chain's `lod` took 23-78 s beside two busy
// loops on this 2-core machine, against 14-20 s with this slot (docs/simplification.md,
// "Lookahead on a busy machine"). Taking a job back means the loop never waits for a thread
// that has not begun.
#pragma once

#include <atomic>
#include <condition_variable>
#include <mutex>

namespace crowdbake {

class HandoverSlot {
 public:
  // The loop's side. post() once the job's inputs are written; then either take_back()
  // succeeds (the job will never run) or wait_done() returns once it has run.
  void post();
  bool take_back();
  void wait_done();

  // The lookahead thread's side: wait_job() is false once stop() was called; finish() after
  // each job.
  bool wait_job();
  void finish();
  void stop();

 private:
  enum State : int { kEmpty, kPosted, kTaken, kDone };

  template <class Ready>
  void wait_until(Ready ready);
  void set(State s);

  std::atomic<int> state_{kEmpty};
  std::atomic<bool> stopping_{false};
  std::mutex mutex_;
  std::condition_variable changed_;
};

}  // namespace crowdbake
