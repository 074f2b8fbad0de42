#include "core/keyframes.h"

#include <algorithm>

namespace pbm {

Real evaluate_keys(Interpolation interpolation, const std::vector<Keyframe>& k, Real t) {
  if (t <= k.front().time) return k.front().value;
  if (t >= k.back().time) return k.back().value;
  const auto it = std::upper_bound(k.begin(), k.end(), t,
                                   [](Real time, const Keyframe& key) { return time < key.time; });
  const std::size_t i = static_cast<std::size_t>(it - k.begin()) - 1;
  const Keyframe& a = k[i];
  if (interpolation == Interpolation::step) return a.value;
  const Keyframe& b = k[i + 1];
  const Real h = b.time - a.time;
  const Real x = (t - a.time) / h;
  if (interpolation == Interpolation::linear) return a.value + x * (b.value - a.value);
  // Catmull-Rom slopes (one-sided at the ends), scaled to the interval.
  auto slope = [&k](std::size_t j) {
    const std::size_t lo = j == 0 ? 0 : j - 1;
    const std::size_t hi = std::min(j + 1, k.size() - 1);
    return (k[hi].value - k[lo].value) / (k[hi].time - k[lo].time);
  };
  const Real m0 = slope(i) * h, m1 = slope(i + 1) * h;
  const Real x2 = x * x, x3 = x2 * x;
  return (2 * x3 - 3 * x2 + 1) * a.value + (x3 - 2 * x2 + x) * m0 + (-2 * x3 + 3 * x2) * b.value +
         (x3 - x2) * m1;
}

Real evaluate_keys_rate(Interpolation interpolation, const std::vector<Keyframe>& k, Real t) {
  if (k.size() < 2 || t < k.front().time || t >= k.back().time) return 0;
  if (interpolation == Interpolation::step) return 0;
  const auto it = std::upper_bound(k.begin(), k.end(), t,
                                   [](Real time, const Keyframe& key) { return time < key.time; });
  const std::size_t i = static_cast<std::size_t>(it - k.begin()) - 1;
  const Keyframe& a = k[i];
  const Keyframe& b = k[i + 1];
  const Real h = b.time - a.time;
  if (interpolation == Interpolation::linear) return (b.value - a.value) / h;
  // The derivative of evaluate_track's Hermite cubic, d/dt = (1 / h) d/dx.
  auto slope = [&k](std::size_t j) {
    const std::size_t lo = j == 0 ? 0 : j - 1;
    const std::size_t hi = std::min(j + 1, k.size() - 1);
    return (k[hi].value - k[lo].value) / (k[hi].time - k[lo].time);
  };
  const Real m0 = slope(i) * h, m1 = slope(i + 1) * h;
  const Real x = (t - a.time) / h, x2 = x * x;
  return ((6 * x2 - 6 * x) * a.value + (3 * x2 - 4 * x + 1) * m0 + (-6 * x2 + 6 * x) * b.value +
          (3 * x2 - 2 * x) * m1) /
         h;
}

}  // namespace pbm
