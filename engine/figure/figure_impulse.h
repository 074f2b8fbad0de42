// Impulse events (sec. 15.3; fig. 15.6, the soldier felled by "a large initial impulse on the
// chest"): at an instant, a spatial impulse P on one segment changes the figure's velocities
// while its positions stay. In joint coordinates, as at an impact (figure/figure_impact.h), the
// joint impulses drop out (15.7) and H dv = J^T P. The articulated-body method gives dv without
// forming H: with the figure at rest, no gravity and no joint forces, its qddot under the
// external force P is exactly H^-1 J^T P, in time linear in the DOF.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "core/spatial.h"
#include "figure/figure_def.h"
#include "figure/figure_model.h"
#include "figure/figure_workspace.h"
#include "figure/site_ref.h"

namespace pbm {

struct CompiledImpulse {
  Real time = 0;
  SiteRef site;
  Vec3 linear = Vec3::Zero(), angular = Vec3::Zero();
  ImpulseFrame frame = ImpulseFrame::world;
};

// The impulses of `def`, checked (time >= 0 and finite, the segment and site exist, the vectors
// finite and not both zero) and sorted by time (equal times in scene order). `path`: the figure's
// JSON path.
std::vector<CompiledImpulse> compile_impulses(const FigureDef& def, const FigureModel& figure,
                                              const std::string& file, const std::string& path);

// Scratch of apply_impulse for figures of up to n_v DOF and `segments` segments.
struct ImpulseScratch {
  std::vector<ForceVector> forces;
  std::vector<SpatialTransform> world;
  VecX zero, dv;
};
void size_impulse_scratch(int n_v, int segments, ImpulseScratch& scratch);

// Adds H^-1 J^T P to v (n_v) at q for the impulse, and returns its work, the kinetic energy it
// gave: (V- + V+) . P / 2 with V the struck segment's spatial velocity before and after [J].
Real apply_impulse(const FigureModel& figure, const Real* q, Real* v,
                   const CompiledImpulse& impulse, ImpulseScratch& scratch, FigureWorkspace& ws);

}  // namespace pbm
