#pragma once
/// \file checked_growth.hpp
/// Sizing a large vector with Ctrl-C checks (cancel.hpp). The first write to fresh memory costs the
/// system about a third of a second per few hundred MB here (pages are zeroed as they are first
/// touched); one resize or value-initialising constructor of that size runs with no check.

#include <algorithm>
#include <cstddef>
#include <vector>

#include "base/cancel.hpp"

namespace sculpt {

/// Resizes `v` to `n` elements (value-initialised, or copies of `value`) a million at a time,
/// checking for Ctrl-C between the steps. The storage is reserved first: it never moves.
template <class T>
void resize_checked(std::vector<T>& v, std::size_t n, const T& value = T()) {
  constexpr std::size_t kStep = std::size_t(1) << 20;
  v.reserve(n);
  while (v.size() < n) {
    check_cancel();
    v.resize(std::min(n, v.size() + kStep), value);
  }
  if (v.size() > n) v.resize(n);
}

}  // namespace sculpt
