// `pbm bench figures`: microseconds per call of the articulated-body method (sec. 15.2) and per
// step (ABA, semi-implicit Euler, quaternion renormalization) for revolute chains and binary trees
// of 7 ... 120 DOF, side by side in the same run with Bullet's btMultiBody on the same tree (its
// ABA with gravity as link forces, and its step without contacts), fastest of alternating rounds.
#pragma once

namespace pbm {

int run_bench_figures();

}  // namespace pbm
