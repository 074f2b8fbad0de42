// One classical Runge-Kutta step of a figure's (q, v) for the tests that integrate figures on
// their own (outside the World): rates(q, v, q_dot, v_dot) fills q_dot (n_q) and v_dot (n_v);
// quaternions are renormalized after the step (sec. 6.1).
#pragma once

#include "figure/figure_model.h"

namespace pbm::test {

template <class Rates>
void figure_rk4_step(const FigureModel& figure, VecX& q, VecX& v, Real h, Rates&& rates) {
  VecX k1q, k1v, k2q, k2v, k3q, k3v, k4q, k4v;
  rates(q, v, k1q, k1v);
  rates(q + 0.5 * h * k1q, v + 0.5 * h * k1v, k2q, k2v);
  rates(q + 0.5 * h * k2q, v + 0.5 * h * k2v, k3q, k3v);
  rates(q + h * k3q, v + h * k3v, k4q, k4v);
  q += h / 6 * (k1q + 2 * k2q + 2 * k3q + k4q);
  v += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
  figure_normalize(figure, q.data());
}

}  // namespace pbm::test
