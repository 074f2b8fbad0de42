#include "core/keyframes.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace pbm {
namespace {

// The interval [a, b] of keys around t (t strictly inside the keys' span), with t's place x in
// it and, for smooth curves, the Catmull-Rom slopes at its ends (one-sided at the ends of the
// keys) scaled to the interval: the cubic is H(x) = h00 a + h10 m0 + h01 b + h11 m1.
struct Interval {
  std::size_t i = 0;
  Real h = 0, x = 0, m0 = 0, m1 = 0;
};

Interval locate(const std::vector<Keyframe>& k, Real t) {
  const auto it = std::upper_bound(k.begin(), k.end(), t,
                                   [](Real time, const Keyframe& key) { return time < key.time; });
  Interval s;
  s.i = static_cast<std::size_t>(it - k.begin()) - 1;
  s.h = k[s.i + 1].time - k[s.i].time;
  s.x = (t - k[s.i].time) / s.h;
  const auto slope = [&k](std::size_t j) {
    const std::size_t lo = j == 0 ? 0 : j - 1;
    const std::size_t hi = std::min(j + 1, k.size() - 1);
    return (k[hi].value - k[lo].value) / (k[hi].time - k[lo].time);
  };
  s.m0 = slope(s.i) * s.h;
  s.m1 = slope(s.i + 1) * s.h;
  return s;
}

}  // namespace

Real evaluate_keys(Interpolation interpolation, const std::vector<Keyframe>& k, Real t) {
  if (t <= k.front().time) return k.front().value;
  if (t >= k.back().time) return k.back().value;
  const Interval s = locate(k, t);
  const Real a = k[s.i].value, b = k[s.i + 1].value;
  if (interpolation == Interpolation::step) return a;
  if (interpolation == Interpolation::linear) return a + s.x * (b - a);
  const Real x = s.x, x2 = x * x, x3 = x2 * x;
  return (2 * x3 - 3 * x2 + 1) * a + (x3 - 2 * x2 + x) * s.m0 + (-2 * x3 + 3 * x2) * b +
         (x3 - x2) * s.m1;
}

Real evaluate_keys_rate(Interpolation interpolation, const std::vector<Keyframe>& k, Real t) {
  if (k.size() < 2 || t < k.front().time || t >= k.back().time) return 0;
  if (interpolation == Interpolation::step) return 0;
  const Interval s = locate(k, t);
  const Real a = k[s.i].value, b = k[s.i + 1].value;
  if (interpolation == Interpolation::linear) return (b - a) / s.h;
  // The derivative of evaluate_keys' Hermite cubic, d/dt = (1 / h) d/dx.
  const Real x = s.x, x2 = x * x;
  return ((6 * x2 - 6 * x) * a + (3 * x2 - 4 * x + 1) * s.m0 + (-6 * x2 + 6 * x) * b +
          (3 * x2 - 2 * x) * s.m1) /
         s.h;
}

Real evaluate_keys_acceleration(Interpolation interpolation, const std::vector<Keyframe>& k,
                                Real t) {
  if (interpolation != Interpolation::smooth) return 0;
  if (k.size() < 2 || t < k.front().time || t >= k.back().time) return 0;
  const Interval s = locate(k, t);
  const Real a = k[s.i].value, b = k[s.i + 1].value, x = s.x;
  // d^2/dt^2 = (1 / h^2) d^2/dx^2 of the cubic.
  return ((12 * x - 6) * a + (6 * x - 4) * s.m0 + (-12 * x + 6) * b + (6 * x - 2) * s.m1) /
         (s.h * s.h);
}

void require_keyframes(const std::vector<Keyframe>& keys, const std::string& file,
                       const std::string& at) {
  if (keys.empty()) throw Error(file, at, "needs at least one [time, value] key");
  for (std::size_t k = 0; k < keys.size(); ++k) {
    if (!std::isfinite(keys[k].time) || !std::isfinite(keys[k].value)) {
      throw Error(file, at + "[" + std::to_string(k) + "]", "must be finite");
    }
    if (k > 0 && !(keys[k].time > keys[k - 1].time)) {
      throw Error(file, at + "[" + std::to_string(k) + "]", "times must increase strictly");
    }
  }
}

}  // namespace pbm
