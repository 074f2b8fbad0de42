// Bitwise equality of vectors: the determinism checks and the caches keyed on a state compare
// bits, not values (0.0 == -0.0 and NaN != NaN would both mislead them).
#pragma once

#include <cstdint>
#include <cstring>

#include "core/types.h"

namespace pbm {

// FNV-1a: mixes n bytes into the hash h (start from kFnvOffset). Equal hashes of states are the
// determinism checks' evidence of equal bits.
inline constexpr std::uint64_t kFnvOffset = 1469598103934665603ull;
inline void fnv1a_mix(std::uint64_t& h, const void* data, std::size_t n) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < n; ++i) {
    h ^= bytes[i];
    h *= 1099511628211ull;
  }
}

inline bool same_bits(const VecX& a, const VecX& b) {
  return a.size() == b.size() &&
         std::memcmp(a.data(), b.data(), sizeof(Real) * static_cast<std::size_t>(a.size())) == 0;
}

}  // namespace pbm
