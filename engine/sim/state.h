// State: minimal restartable plain data (DESIGN §1). Layout described in sim/model.h.
#pragma once

#include <cstdint>

#include "core/types.h"
#include "sim/model.h"

namespace pbm {

struct State {
  Real time = 0;  // [s]
  VecX q;         // generalized coordinates of every body, n_q
  VecX v;         // generalized velocities of every body, n_v
};

State initial_state(const Model& model);

// FNV-1a over the bytes of time, q and v: equal hashes <=> bit-identical states.
std::uint64_t hash_state(const State& state);

// Quaternion (w,x,y,z) helpers for q_theta.
Mat3 rotation_from_quaternion(const Vec4& q);                 // (3.7), q normalized first
Vec4 quaternion_rate(const Vec4& q, const Vec3& omega_body);  // 1/2 q (x) (0, omega)

}  // namespace pbm
