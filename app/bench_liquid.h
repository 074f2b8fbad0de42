// `pbm bench liquid`: nanoseconds per cell per substep of the liquid grid (engine/liquid/, ch. 16)
// on 3D dam breaks of 32^3, 64^3 and 128^3 cells, for each advection and each pressure solver,
// the step without its pressure solve beside a memory-bandwidth probe in the same process (a
// substep cannot be faster than streaming its arrays), and each solver's iterations to a 1e-6
// relative residual.
#pragma once

namespace pbm {

// largest: the largest grid's cells per axis (32, 64 or 128).
int run_bench_liquid(int largest);

}  // namespace pbm
