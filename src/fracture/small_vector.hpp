#pragma once
// A vector that holds its first N elements in place and only beyond them on the heap.
// Fragment meshing cuts hundreds of thousands of tet faces into convex polygons of 3–8 corners;
// with std::vector each polygon was an allocation and the allocator was the largest cost of the
// meshing (docs/fragments.md, "Speed"). Contiguous, so std::span and the std algorithms take it.
#include <algorithm>
#include <cstddef>
#include <initializer_list>
#include <memory>
#include <new>
#include <utility>

namespace fissure::detail {

template <class T, std::size_t N>
class SmallVector {
public:
  using value_type = T;
  using size_type = std::size_t;
  using iterator = T*;
  using const_iterator = const T*;

  SmallVector() = default;
  SmallVector(std::initializer_list<T> items) { append(items.begin(), items.end()); }
  SmallVector(const SmallVector& other) { append(other.begin(), other.end()); }
  SmallVector(SmallVector&& other) noexcept { take(std::move(other)); }
  SmallVector& operator=(const SmallVector& other) {
    if (this != &other) {
      clear();
      append(other.begin(), other.end());
    }
    return *this;
  }
  SmallVector& operator=(SmallVector&& other) noexcept {
    if (this != &other) {
      release();
      take(std::move(other));
    }
    return *this;
  }
  ~SmallVector() { release(); }

  T* data() { return m_data; }
  const T* data() const { return m_data; }
  std::size_t size() const { return m_size; }
  bool empty() const { return m_size == 0; }
  T* begin() { return m_data; }
  T* end() { return m_data + m_size; }
  const T* begin() const { return m_data; }
  const T* end() const { return m_data + m_size; }
  T& operator[](std::size_t i) { return m_data[i]; }
  const T& operator[](std::size_t i) const { return m_data[i]; }
  T& front() { return m_data[0]; }
  const T& front() const { return m_data[0]; }
  T& back() { return m_data[m_size - 1]; }
  const T& back() const { return m_data[m_size - 1]; }

  void reserve(std::size_t n) {
    if (n <= m_capacity) return;
    T* fresh = static_cast<T*>(::operator new(n * sizeof(T), std::align_val_t(alignof(T))));
    for (std::size_t i = 0; i < m_size; ++i) {
      ::new (fresh + i) T(std::move(m_data[i]));
      m_data[i].~T();
    }
    if (!is_inline()) ::operator delete(m_data, std::align_val_t(alignof(T)));
    m_data = fresh;
    m_capacity = n;
  }
  void push_back(const T& x) { emplace_back(x); }
  void push_back(T&& x) { emplace_back(std::move(x)); }
  template <class... Args>
  T& emplace_back(Args&&... args) {
    if (m_size == m_capacity) {
      T copy(std::forward<Args>(args)...);  // args may refer to an element that reserve() moves
      reserve(2 * m_capacity);
      return *::new (m_data + m_size++) T(std::move(copy));
    }
    return *::new (m_data + m_size++) T(std::forward<Args>(args)...);
  }
  void pop_back() { m_data[--m_size].~T(); }
  /// Shrinks to n elements (n ≤ size()), as after std::unique or std::remove_if.
  void truncate(std::size_t n) {
    while (m_size > n) pop_back();
  }
  void clear() { truncate(0); }

private:
  bool is_inline() const { return m_data == inline_data(); }
  T* inline_data() { return std::launder(reinterpret_cast<T*>(m_inline)); }
  const T* inline_data() const { return std::launder(reinterpret_cast<const T*>(m_inline)); }
  template <class It>
  void append(It first, It last) {
    reserve(m_size + static_cast<std::size_t>(last - first));
    for (; first != last; ++first) ::new (m_data + m_size++) T(*first);
  }
  // Takes other's elements; this is empty and inline.
  void take(SmallVector&& other) {
    if (other.is_inline()) {
      for (std::size_t i = 0; i < other.m_size; ++i) ::new (m_data + i) T(std::move(other.m_data[i]));
      m_size = other.m_size;
      other.clear();
    } else {
      m_data = other.m_data;
      m_size = other.m_size;
      m_capacity = other.m_capacity;
      other.m_data = other.inline_data();
      other.m_size = 0;
      other.m_capacity = N;
    }
  }
  void release() {
    clear();
    if (!is_inline()) ::operator delete(m_data, std::align_val_t(alignof(T)));
    m_data = inline_data();
    m_capacity = N;
  }

  alignas(T) unsigned char m_inline[N * sizeof(T)];
  T* m_data = inline_data();
  std::size_t m_size = 0;
  std::size_t m_capacity = N;
};

}  // namespace fissure::detail
