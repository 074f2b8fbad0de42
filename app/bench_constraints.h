// `pbm bench constraints`: wall time per step of the constraint-force solve of sec. 7.3
// (assembling N by (7.36)-(7.41) and solving (7.33)) for chains and binary trees of k = 1 ... 1000
// point constraints between small rigid parts, dense LU against sparse LDL^T, with the fitted
// growth exponent (log-log slope over k >= 10) of each.
#pragma once

namespace pbm {

int run_bench_constraints(int max_constraints);

}  // namespace pbm
