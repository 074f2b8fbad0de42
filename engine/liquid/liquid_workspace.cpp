#include "liquid/liquid_workspace.h"

#include "liquid/cell_labels.h"

namespace pbm {

void size_liquid_workspace(const LiquidModel& model, LiquidWorkspace& ws) {
  const auto n = static_cast<std::size_t>(model.grid.size);
  ws.flags.assign(n, CellFlag::empty);
  ws.fill.assign(n, 0.0);
  ws.count.assign(n, 0);
  ws.previous.resize(model.grid.size);
  ws.pressure_start.assign(n, 0.0);
  for (auto& w : ws.transfer_weight) {
    w.assign(model.def.advection == LiquidAdvection::flip ? n : 0, 0.0);
  }
  ws.extrapolation.known.assign(n, 0);
  ws.extrapolation.frontier.clear();
  ws.extrapolation.added.clear();
  ws.cell_of_row.clear();
  ws.cell_of_row.reserve(static_cast<std::size_t>(model.grid.interior_cells()));
  ws.diag.assign(n, 0.0);
  ws.target.assign(n, 0.0);
  for (auto& scale : ws.face_scale) scale.assign(n, 1.0);
  for (auto* v : {&ws.dp, &ws.r, &ws.z, &ws.s, &ws.q, &ws.precon}) v->assign(n, 0.0);
  ws.inflow_velocity.assign(model.inflows.size(), Vec3::Zero());
  ws.height_next.assign(static_cast<std::size_t>(model.def.surface == SurfaceMethod::height_field
                                                     ? column_count(model)
                                                     : 0),
                        0.0);
  size_moving_solids(model, ws.moving);
  if (model.def.solver == PressureSolver::mgpcg) size_multigrid(model.grid, ws.multigrid);
}

}  // namespace pbm
