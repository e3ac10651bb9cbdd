#pragma once
/// \file chunked_vector.hpp
/// A sequence indexed like std::vector whose storage never moves: it grows by chunks of doubling
/// size (16, 32, 64, ... 2048 elements), then of 4096 elements each, so appending never relocates
/// the elements already there and never touches more memory than it writes. The fixed size of the
/// later chunks bounds the unused room of a long list by one chunk (doubling to the end left up to
/// half of it unused: 47 % of a 89,000-fragment result, 8 MB). A std::vector of large elements that doubles moves
/// all of them at once and faults in a buffer twice their size: for the node polygons of a tree
/// of 90,000 nodes (about 270 bytes each) that was 50-150 ms in one set operation, now spread over
/// the operations that fill the new chunk. References to elements stay valid while it grows.

#include <algorithm>
#include <bit>
#include <compare>
#include <cstddef>
#include <iterator>
#include <memory>
#include <utility>
#include <vector>

#include "base/assert.hpp"
#include "base/index_iterator.hpp"

namespace sculpt {

template <class T>
class ChunkedVector {
 public:
  using value_type = T;
  using size_type = std::size_t;
  using reference = T&;
  using const_reference = const T&;

  ChunkedVector() = default;
  ChunkedVector(const ChunkedVector& other) {
    reserve(other.size_);
    for (const T& x : other) emplace_back(x);
  }
  ChunkedVector(ChunkedVector&& other) noexcept
      : chunks_(std::move(other.chunks_)), size_(std::exchange(other.size_, 0)) {}
  /// The elements of `v`, moved.
  ChunkedVector(std::vector<T>&& v) {  // NOLINT: implicit, as the vectors tree builders fill
    reserve(v.size());
    for (T& x : v) emplace_back(std::move(x));
  }
  ChunkedVector& operator=(const ChunkedVector& other) {
    if (this != &other) {
      ChunkedVector copy(other);
      swap(copy);
    }
    return *this;
  }
  ChunkedVector& operator=(ChunkedVector&& other) noexcept {
    if (this != &other) {
      release();
      chunks_ = std::move(other.chunks_);
      size_ = std::exchange(other.size_, 0);
    }
    return *this;
  }
  ~ChunkedVector() { release(); }

  void swap(ChunkedVector& other) noexcept {
    chunks_.swap(other.chunks_);
    std::swap(size_, other.size_);
  }

  [[nodiscard]] std::size_t size() const { return size_; }
  [[nodiscard]] bool empty() const { return size_ == 0; }
  /// Elements the allocated chunks hold.
  [[nodiscard]] std::size_t capacity() const { return end_of(chunks_.size()); }

  T& operator[](std::size_t i) { return at(i); }
  const T& operator[](std::size_t i) const { return const_cast<ChunkedVector&>(*this).at(i); }
  T& back() { return at(size_ - 1); }
  const T& back() const { return (*this)[size_ - 1]; }

  template <class... Args>
  T& emplace_back(Args&&... args) {
    reserve(size_ + 1);
    T* p = std::construct_at(slot(size_), std::forward<Args>(args)...);
    ++size_;
    return *p;
  }
  void push_back(const T& x) { emplace_back(x); }
  void push_back(T&& x) { emplace_back(std::move(x)); }
  void pop_back() { std::destroy_at(slot(--size_)); }
  void resize(std::size_t n) {
    while (size_ > n) pop_back();
    reserve(n);
    while (size_ < n) emplace_back();
  }
  void clear() { resize(0); }
  /// Allocates chunks for n elements (memory that is not written is not touched).
  void reserve(std::size_t n) {
    while (capacity() < n) {
      chunks_.push_back(std::allocator<T>().allocate(chunk_size(chunks_.size())));
    }
  }
  /// Frees the chunks no element is in.
  void shrink_to_fit() {
    while (!chunks_.empty() && end_of(chunks_.size() - 1) >= size_) {
      std::allocator<T>().deallocate(chunks_.back(), chunk_size(chunks_.size() - 1));
      chunks_.pop_back();
    }
  }

  using iterator = IndexIterator<ChunkedVector, T&>;
  using const_iterator = IndexIterator<const ChunkedVector, const T&>;
  iterator begin() { return {this, 0}; }
  iterator end() { return {this, size_}; }
  const_iterator begin() const { return {this, 0}; }
  const_iterator end() const { return {this, size_}; }

 private:
  static constexpr std::size_t kFirst = 16;  ///< elements of chunk 0; chunk k < kLast holds kFirst * 2^k
  static constexpr std::size_t kLast = 8;    ///< chunks kLast and later hold kFixed elements each
  static constexpr std::size_t kFixed = kFirst << kLast;
  static constexpr std::size_t kHead = kFirst * ((std::size_t(1) << kLast) - 1);  ///< elements before chunk kLast

  static std::size_t chunk_size(std::size_t k) { return k < kLast ? kFirst << k : kFixed; }
  /// Elements in chunks 0..k-1.
  static std::size_t end_of(std::size_t k) {
    return k <= kLast ? kFirst * ((std::size_t(1) << k) - 1) : kHead + (k - kLast) * kFixed;
  }
  T* slot(std::size_t i) {
    if (i >= kHead) return chunks_[kLast + (i - kHead) / kFixed] + (i - kHead) % kFixed;
    // Chunk k < kLast holds indices [end_of(k), end_of(k + 1)), so i / kFirst + 1 lies in [2^k, 2^(k+1)).
    const auto k = std::size_t(std::bit_width(i / kFirst + 1) - 1);
    return chunks_[k] + (i - end_of(k));
  }
  T& at(std::size_t i) {
    SCULPT_ASSERT(i < size_, "ChunkedVector: index past the end");
    return *slot(i);
  }
  void release() {
    clear();
    for (std::size_t k = 0; k < chunks_.size(); ++k) std::allocator<T>().deallocate(chunks_[k], chunk_size(k));
    chunks_.clear();
  }

  std::vector<T*> chunks_;
  std::size_t size_ = 0;
};

}  // namespace sculpt
