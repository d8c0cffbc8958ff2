// A short list held in place: up to kInline elements inside the object, more on the heap.
// The collapse loop keeps one per position (its live faces); a vector's header and its
// separate block cost two cache misses per read where this costs one.
// T must be trivially copyable.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace crowdbake {

template <typename T, uint32_t kInline>
class SmallList {
  static_assert(std::is_trivially_copyable_v<T>);

 public:
  SmallList() = default;
  SmallList(const SmallList&) = delete;
  SmallList& operator=(const SmallList&) = delete;
  SmallList(SmallList&& o) noexcept : size_(o.size_), capacity_(o.capacity_) {
    std::memcpy(&store_, &o.store_, sizeof store_);
    o.size_ = 0, o.capacity_ = kInline;
  }
  ~SmallList() {
    if (on_heap()) delete[] store_.heap;
  }

  T* begin() { return data(); }
  T* end() { return data() + size_; }
  const T* begin() const { return data(); }
  const T* end() const { return data() + size_; }
  size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }

  void push_back(T x) {  // note: by value, so an element of the list itself may be pushed
    if (size_ == capacity_) grow();
    data()[size_++] = x;
  }
  // Removes the element at `it`, keeping the order of the rest.
  void erase(T* it) { erase(it, it + 1); }
  void erase(T* first, T* last) {
    std::copy(last, end(), first);
    size_ -= static_cast<uint32_t>(last - first);
  }
  void clear() { size_ = 0; }

 private:
  bool on_heap() const { return capacity_ > kInline; }
  T* data() { return on_heap() ? store_.heap : reinterpret_cast<T*>(store_.in_place); }
  const T* data() const {
    return on_heap() ? store_.heap : reinterpret_cast<const T*>(store_.in_place);
  }
  void grow() {
    const uint32_t capacity = 2 * capacity_;
    T* heap = new T[capacity];
    std::copy(begin(), end(), heap);
    if (on_heap()) delete[] store_.heap;
    store_.heap = heap;
    capacity_ = capacity;
  }

  uint32_t size_ = 0, capacity_ = kInline;
  // note: the elements in place, or (once they outgrow it) the heap block's address; raw
  // bytes in place, so that T may have default member initialisers.
  union Store {
    alignas(T) unsigned char in_place[kInline * sizeof(T)];
    T* heap;
  } store_{};
};

}  // namespace crowdbake
