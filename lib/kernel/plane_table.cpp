#include "kernel/plane_table.hpp"

#include <algorithm>
#include <atomic>

namespace sculpt::kernel {

namespace {

/// Room a block is given when made or copied: the first block grows from a few planes (most
/// tables are small: a primitive, a curve's solid, a turned box of 18 planes, of which a union
/// may hold 10^4: room for 64 was 3 KB each), the others are made to hold kBlock.
std::size_t block_room(std::size_t k, std::size_t used) {
  const auto full = std::size_t(PlaneTable::kBlock);
  return k == 0 ? std::min(full, std::max<std::size_t>(16, used + used / 2)) : full;
}

}  // namespace

PlaneTable::PlaneTable() {
  const Int128 k = kWorld;
  for (const Plane& p : {Plane{1, 0, 0, -k}, Plane{-1, 0, 0, -k}, Plane{0, 1, 0, -k}, Plane{0, -1, 0, -k},
                         Plane{0, 0, 1, -k}, Plane{0, 0, -1, -k}})
    add(p);
}

PlaneTable::Block& PlaneTable::writable(std::size_t k) {
  std::shared_ptr<Block>& block = storage_[k];
  const std::size_t first = k << kBlockBits;
  const std::size_t used = std::min(std::size_t(kBlock), std::size_t(size_) - first);
  if (block.use_count() > 1) {
    auto own = std::make_shared<Block>();
    own->reserve(block_room(k, used));
    own->assign(block->begin(), block->begin() + std::ptrdiff_t(used));
    block = std::move(own);
  } else {
    // Unshared: writes below are ordered after the other tables' last reads of it (they
    // released their references before the count fell to one).
    std::atomic_thread_fence(std::memory_order_acquire);
    block->resize(used);  // planes a truncate() dropped
  }
  blocks_[k] = block->data();
  return *block;
}

void PlaneTable::append_run(const Plane* p, std::size_t n) {
  while (n > 0) {
    const std::size_t k = std::size_t(size_) >> kBlockBits, at = std::size_t(size_) & std::size_t(kBlock - 1);
    if (k == storage_.size()) {
      storage_.push_back(std::make_shared<Block>());
      storage_.back()->reserve(block_room(k, n));
      blocks_.push_back(nullptr);
    }
    Block& block = writable(k);
    const std::size_t take = std::min(n, std::size_t(kBlock) - at);
    if (block.capacity() < at + take) block.reserve(std::min(std::size_t(kBlock), std::max(at + take, 2 * at)));
    block.insert(block.end(), p, p + take);
    blocks_[k] = block.data();
    size_ += std::int32_t(take);
    p += take, n -= take;
  }
}

std::int32_t PlaneTable::add(const Plane& p, bool auxiliary) {
  const std::int32_t at = size_;
  // The usual case first: room in an unshared last block (its address does not change).
  const std::size_t k = std::size_t(at) >> kBlockBits;
  Block* last = k < storage_.size() ? storage_[k].get() : nullptr;
  if (last && last->size() == (std::size_t(at) & std::size_t(kBlock - 1)) && last->size() < last->capacity() &&
      storage_[k].use_count() == 1) {
    last->push_back(p);
    ++size_;
  } else {
    append_run(&p, 1);
  }
  auxiliary_.push_back(auxiliary);
  return at;
}

std::int32_t PlaneTable::append(const PlaneTable& from, std::int32_t first) {
  const std::int32_t at = size_;
  for (std::int32_t i = first; i < from.size();) {
    const std::int32_t run = std::min(from.size() - i, kBlock - (i & (kBlock - 1)));  // within one source block
    append_run(&from[i], std::size_t(run));
    i += run;
  }
  if (first < from.size()) auxiliary_.insert(auxiliary_.end(), from.auxiliary_.begin() + first, from.auxiliary_.end());
  return at;
}

std::int32_t PlaneTable::append_shared(const PlaneTable& from) {
  const Plane pad = (*this)[0];
  while ((size_ & (kBlock - 1)) != 0) add(pad);
  const std::int32_t at = size_;
  storage_.insert(storage_.end(), from.storage_.begin(), from.storage_.end());
  blocks_.insert(blocks_.end(), from.blocks_.begin(), from.blocks_.end());
  size_ += from.size_;
  auxiliary_.insert(auxiliary_.end(), from.auxiliary_.begin(), from.auxiliary_.end());
  return at;
}

void PlaneTable::reserve(std::size_t n) {
  auxiliary_.reserve(n);
  blocks_.reserve((n + std::size_t(kBlock) - 1) >> kBlockBits);
  storage_.reserve(blocks_.capacity());
}

void PlaneTable::truncate(std::int32_t n) {
  size_ = std::min(size_, std::max(n, std::int32_t(6)));
  const std::size_t blocks = (std::size_t(size_) + std::size_t(kBlock) - 1) >> kBlockBits;
  storage_.resize(blocks);
  blocks_.resize(blocks);
  auxiliary_.resize(std::size_t(size_));
}

void PlaneTable::replace(std::int32_t i, const Plane& p, bool auxiliary) {
  SCULPT_ASSERT(i >= 0 && i < size_, "PlaneTable: plane index outside the table");
  writable(std::size_t(i) >> kBlockBits)[std::size_t(i) & std::size_t(kBlock - 1)] = p;
  auxiliary_[std::size_t(i)] = auxiliary;
}

std::vector<Plane> PlaneTable::to_vector() const {
  std::vector<Plane> out;
  out.reserve(std::size_t(size_));
  for (std::int32_t i = 0; i < size_; ++i) out.push_back((*this)[i]);
  return out;
}

bool PlaneTable::shares_storage_with(const PlaneTable& other) const {
  for (const auto& a : storage_)
    for (const auto& b : other.storage_)
      if (a == b) return true;
  return false;
}

}  // namespace sculpt::kernel
