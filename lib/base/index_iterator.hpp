#pragma once
/// \file index_iterator.hpp
/// A random-access iterator over a container read by index (owner[i]): what ChunkedVector and
/// the compact fragment list (bsp/fragment_list.hpp) iterate with. `Reference` is what owner[i]
/// gives: a reference, or a value for containers that hand out views.

#include <compare>
#include <cstddef>
#include <iterator>
#include <memory>
#include <type_traits>

namespace sculpt {

template <class Owner, class Reference>
class IndexIterator {
 public:
  using iterator_category = std::random_access_iterator_tag;
  using value_type = std::remove_cvref_t<Reference>;
  using difference_type = std::ptrdiff_t;
  using reference = Reference;
  using pointer = std::conditional_t<std::is_reference_v<Reference>, std::remove_reference_t<Reference>*, void>;

  IndexIterator() = default;
  IndexIterator(Owner* owner, std::size_t i) : owner_(owner), i_(difference_type(i)) {}
  reference operator*() const { return (*owner_)[std::size_t(i_)]; }
  pointer operator->() const requires std::is_reference_v<Reference> { return std::addressof(**this); }
  reference operator[](difference_type d) const { return (*owner_)[std::size_t(i_ + d)]; }
  IndexIterator& operator++() { return *this += 1; }
  IndexIterator& operator--() { return *this -= 1; }
  IndexIterator operator++(int) {
    IndexIterator old = *this;
    ++i_;
    return old;
  }
  IndexIterator operator--(int) {
    IndexIterator old = *this;
    --i_;
    return old;
  }
  IndexIterator& operator+=(difference_type d) {
    i_ += d;
    return *this;
  }
  IndexIterator& operator-=(difference_type d) { return *this += -d; }
  friend IndexIterator operator+(IndexIterator a, difference_type d) { return a += d; }
  friend IndexIterator operator+(difference_type d, IndexIterator a) { return a += d; }
  friend IndexIterator operator-(IndexIterator a, difference_type d) { return a -= d; }
  friend difference_type operator-(const IndexIterator& a, const IndexIterator& b) { return a.i_ - b.i_; }
  friend bool operator==(const IndexIterator& a, const IndexIterator& b) { return a.i_ == b.i_; }
  friend auto operator<=>(const IndexIterator& a, const IndexIterator& b) { return a.i_ <=> b.i_; }

 private:
  Owner* owner_ = nullptr;
  difference_type i_ = 0;
};

}  // namespace sculpt
