#include "base/cancel.hpp"

namespace sculpt::detail {

void throw_cancelled() {
  if (cancel_shields.load(std::memory_order_relaxed) > 0) return;
  throw Cancelled();
}

}  // namespace sculpt::detail
