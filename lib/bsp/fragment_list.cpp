#include "bsp/fragment_list.hpp"

#include <algorithm>

#include "base/assert.hpp"

namespace sculpt {

namespace {

// Corner blocks double from 16 corners up to 1024 (40 KB): a short list (a cell's pieces) stays
// small, and a long one leaves at most one block's room unused at its end.
constexpr std::size_t kFirstChunk = 16;
constexpr std::size_t kLargestChunk = 1024;
// append() copies the other list's corners below this many, and takes over its blocks above it.
constexpr std::size_t kAdoptCorners = 4096;

}  // namespace

FragmentList::FragmentList(const FragmentList& other) {
  records_.reserve(other.size());
  std::size_t total = 0;
  for (const Record& r : other.records_) total += r.count;
  if (total > 0) {  // one block for all: the copy leaves no room unused
    kernel::Corner* block = std::allocator<kernel::Corner>().allocate(total);
    chunks_.push_back({block, std::uint32_t(total), 0});
  }
  for (const FragmentRef f : other) push_back(f.polygon, f.flip);
}

FragmentList& FragmentList::operator=(const FragmentList& other) {
  if (this != &other) {
    FragmentList copy(other);
    swap(copy);
  }
  return *this;
}

FragmentList::FragmentList(FragmentList&& other) noexcept
    : records_(std::move(other.records_)), chunks_(std::exchange(other.chunks_, {})) {}

FragmentList& FragmentList::operator=(FragmentList&& other) noexcept {
  if (this != &other) {
    release();
    records_ = std::move(other.records_);
    chunks_ = std::exchange(other.chunks_, {});
  }
  return *this;
}

void FragmentList::swap(FragmentList& other) noexcept {
  records_.swap(other.records_);
  chunks_.swap(other.chunks_);
}

void FragmentList::release() {
  for (const Chunk& c : chunks_) std::allocator<kernel::Corner>().deallocate(c.corners, c.capacity);
  chunks_.clear();
  ChunkedVector<Record>().swap(records_);
}

void FragmentList::clear() { release(); }

std::pair<std::uint32_t, std::uint32_t> FragmentList::allot(std::size_t n) {
  if (chunks_.empty() || chunks_.back().capacity - chunks_.back().used < n) {
    const std::size_t size =
        std::max(std::min(kFirstChunk << std::min<std::size_t>(chunks_.size(), 16), kLargestChunk), n);
    SCULPT_ASSERT(size < (std::size_t(1) << 31), "FragmentList: a block of 2^31 corners");
    chunks_.push_back({std::allocator<kernel::Corner>().allocate(size), std::uint32_t(size), 0});
  }
  Chunk& c = chunks_.back();
  const std::uint32_t offset = c.used;
  c.used += std::uint32_t(n);
  return {std::uint32_t(chunks_.size() - 1), offset};
}

void FragmentList::push_back(kernel::PolygonView polygon, bool flip) {
  const std::size_t n = polygon.corners.size();
  const auto [chunk, offset] = allot(n);
  std::uninitialized_copy(polygon.corners.begin(), polygon.corners.end(), chunks_[chunk].corners + offset);
  records_.push_back({polygon.support, chunk, offset, std::uint32_t(n), flip ? 1u : 0u});
}

void FragmentList::pop_back() {
  const Record& r = records_.back();
  Chunk& last = chunks_.back();
  if (r.chunk + 1 == chunks_.size() && r.offset + r.count == last.used) last.used = r.offset;  // room given back
  records_.pop_back();
}

void FragmentList::replace(std::size_t i, kernel::PolygonView polygon, bool flip) {
  const std::size_t n = polygon.corners.size();
  Record r = records_[i];
  if (n > r.count) {  // new room (allot moves no stored corner, so `polygon` stays valid)
    const auto [chunk, offset] = allot(n);
    r.chunk = chunk, r.offset = offset;
  }
  kernel::Corner* to = chunks_[r.chunk].corners + r.offset;
  if (to != polygon.corners.data()) std::copy(polygon.corners.begin(), polygon.corners.end(), to);
  r.support = polygon.support;
  r.count = std::uint32_t(n);
  r.flip = flip ? 1u : 0u;
  records_[i] = r;
}

void FragmentList::append(FragmentList&& other) {
  if (&other == this || other.empty()) return;
  std::size_t corners = 0;
  for (const Chunk& c : other.chunks_) corners += c.used;
  if (corners < kAdoptCorners || empty()) {
    if (empty()) {
      swap(other);
    } else {
      records_.reserve(size() + other.size());
      for (const FragmentRef f : other) push_back(f.polygon, f.flip);
    }
    other.release();
    return;
  }
  const auto shift = std::uint32_t(chunks_.size());
  chunks_.insert(chunks_.end(), other.chunks_.begin(), other.chunks_.end());
  other.chunks_.clear();
  records_.reserve(size() + other.size());
  for (const Record& r : other.records_) {
    Record moved = r;
    moved.chunk += shift;
    records_.push_back(moved);
  }
  other.records_.clear();
}

void FragmentList::pack_if_sparse() {
  std::size_t stored = 0, live = 0;
  for (const Chunk& c : chunks_) stored += c.used;
  for (const Record& r : records_) live += r.count;
  if (4 * (stored - live) >= live && stored > live) {
    FragmentList packed(*this);
    swap(packed);
  }
}

std::size_t FragmentList::bytes() const {
  std::size_t n = records_.capacity() * sizeof(Record) + chunks_.capacity() * sizeof(Chunk);
  for (const Chunk& c : chunks_) n += c.capacity * sizeof(kernel::Corner);
  return n;
}

}  // namespace sculpt
