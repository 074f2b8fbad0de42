// Bitwise equality of vectors: the determinism checks and the caches keyed on a state compare
// bits, not values (0.0 == -0.0 and NaN != NaN would both mislead them).
#pragma once

#include <cstring>

#include "core/types.h"

namespace pbm {

inline bool same_bits(const VecX& a, const VecX& b) {
  return a.size() == b.size() &&
         std::memcmp(a.data(), b.data(), sizeof(Real) * static_cast<std::size_t>(a.size())) == 0;
}

}  // namespace pbm
