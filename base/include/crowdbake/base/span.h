// Span<T>: a pointer and a count (C++17 has no std::span). Jobs take their inputs and
// outputs as spans so they never own or allocate memory (ozz-animation's span). One type for
// every library: formats' progressive-mesh view, the runtime's jobs and the effects.
#pragma once

#include <cstddef>
#include <type_traits>
#include <utility>

namespace crowdbake {

template <typename T>
class Span {
 public:
  constexpr Span() = default;
  constexpr Span(T* data, size_t size) : data_(data), size_(size) {}
  template <size_t N>
  constexpr Span(T (&array)[N]) : data_(array), size_(N) {}  // NOLINT: implicit on purpose
  // Any contiguous container with data() and size() (std::vector, std::array, Span<U>):
  // Span<const T> binds to const containers, Span<T> only to mutable ones.
  template <typename C, typename = std::enable_if_t<
                            std::is_convertible_v<decltype(std::declval<C&>().data()), T*>>>
  constexpr Span(C& container)  // NOLINT: implicit on purpose
      : data_(container.data()), size_(container.size()) {}

  constexpr T* data() const { return data_; }
  constexpr size_t size() const { return size_; }
  constexpr bool empty() const { return size_ == 0; }
  constexpr T& operator[](size_t i) const { return data_[i]; }
  constexpr T* begin() const { return data_; }
  constexpr T* end() const { return data_ + size_; }
  // Elements [offset, offset + count); the caller keeps it inside the span.
  constexpr Span subspan(size_t offset, size_t count) const { return {data_ + offset, count}; }

 private:
  T* data_ = nullptr;
  size_t size_ = 0;
};

}  // namespace crowdbake
