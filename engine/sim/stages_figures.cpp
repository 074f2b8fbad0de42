#include "sim/stages_figures.h"

#include <algorithm>

#include "core/quaternion.h"
#include "figure/articulated_body.h"
#include "figure/figure_impact.h"
#include "figure/figure_kinematics.h"

namespace pbm::stages {

namespace {

// A figure's slices of the World's q, v and their rates.
const Real* q_of(const FigureModel& f, const VecX& q) {
  return q.data() + f.state_q_offset;
}
const Real* v_of(const FigureModel& f, const VecX& v) {
  return v.data() + f.state_v_offset;
}

draw::PrimitiveShape primitive_of(SegmentShapeKind kind) {
  switch (kind) {
    case SegmentShapeKind::box:
      return draw::PrimitiveShape::box;
    case SegmentShapeKind::sphere:
      return draw::PrimitiveShape::sphere;
    case SegmentShapeKind::cylinder:
      return draw::PrimitiveShape::cylinder;
    case SegmentShapeKind::capsule:
      return draw::PrimitiveShape::capsule;
  }
  return draw::PrimitiveShape::box;
}

// The joint forces of the passive figure: its joints' damping, tau = -d q-dot per DOF.
void joint_damping(const FigureModel& figure, const Real* v, Real* tau) {
  for (const SegmentModel& s : figure.segments) {
    const int n = joint_v_size(s.joint.kind);
    for (int k = 0; k < n; ++k) tau[s.v_offset + k] = -s.damping * v[s.v_offset + k];
  }
}

}  // namespace

bool figures_present(const Model& model) {
  return !model.figures.empty();
}

void size_figures(const Model& model, Workspace& ws) {
  FiguresWorkspace& fw = ws.figures.emplace();
  fw.each.resize(model.figures.size());
  int n_v = 0, n_segments = 0;
  for (std::size_t f = 0; f < model.figures.size(); ++f) {
    const FigureModel& figure = model.figures[f].model;
    size_figure_workspace(figure, fw.each[f]);
    n_v = std::max(n_v, figure.n_v);
    n_segments = std::max(n_segments, figure.size());
  }
  fw.tau.setZero(n_v);
  fw.world.reserve(static_cast<std::size_t>(n_segments));
}

void figure_dynamics(const RateContext& c) {
  FiguresWorkspace& fw = *c.ws.figures;
  for (std::size_t f = 0; f < c.model.figures.size(); ++f) {
    const FigureModel& figure = c.model.figures[f].model;
    const Real* v = v_of(figure, c.v);
    joint_damping(figure, v, fw.tau.data());
    // Gravity as the base's acceleration, at its value of the moment (tracks may drive it).
    forward_dynamics(figure, q_of(figure, c.q), v, fw.tau.data(), {}, c.ws.drive.gravity,
                     fw.each[f], c.v_dot.data() + figure.state_v_offset);
  }
}

void figure_kinematics(const RateContext& c) {
  figure_kinematic_rates(c.model, c.q, c.v, c.q_dot);
}

void figure_kinematic_rates(const Model& model, const VecX& q, const VecX& v, VecX& q_dot) {
  for (const CompiledFigure& compiled : model.figures) {
    const FigureModel& figure = compiled.model;
    figure_q_dot(figure, q_of(figure, q), v_of(figure, v), q_dot.data() + figure.state_q_offset);
  }
}

void figure_renormalize(const SubstepContext& c) {
  for (const CompiledFigure& compiled : c.model.figures) {
    figure_normalize(compiled.model, c.state.q.data() + compiled.model.state_q_offset);
  }
}

void measure_figures(const Model& model, const State& state, Workspace& ws, FrameStats& stats) {
  FiguresWorkspace& fw = *ws.figures;
  for (std::size_t f = 0; f < model.figures.size(); ++f) {
    const FigureModel& figure = model.figures[f].model;
    FigureWorkspace& w = fw.each[f];
    pbm::figure_kinematics(figure, q_of(figure, state.q), v_of(figure, state.v), w);
    segment_world_transforms(figure, w, fw.world);
    FigureFrameStats& out = stats.figures[f];
    out.kinetic = out.potential = 0;
    for (int i = 0; i < figure.size(); ++i) {
      const SpatialInertia& I = figure.segments[i].inertia;
      const MotionVector vi = motion_from_vec6(w.v[i]);
      out.kinetic += 0.5 * dot(vi, I * vi);
      // The centre of mass in the world: x = r + E^T c for the world -> segment transform.
      const Vec3 centre = fw.world[i].r + fw.world[i].E.transpose() * I.c;
      out.potential -= I.m * ws.drive.gravity.dot(centre);
    }
  }
}

std::string describe_figure_failure(const Model& model, const State& state) {
  for (const CompiledFigure& compiled : model.figures) {
    const FigureModel& figure = compiled.model;
    for (const SegmentModel& s : figure.segments) {
      const auto q =
          state.q.segment(figure.state_q_offset + s.q_offset, joint_q_size(s.joint.kind));
      const auto v =
          state.v.segment(figure.state_v_offset + s.v_offset, joint_v_size(s.joint.kind));
      if (q.allFinite() && v.allFinite()) continue;
      return "figure '" + figure.name + "', segment '" + s.name + "': its joint's " +
             (q.allFinite() ? "velocity" : "position") + " became NaN or infinite";
    }
  }
  return {};
}

void add_figure_drawables(const Model& model, const Inputs& inputs, const State& state,
                          Workspace& ws, draw::Snapshot& snap) {
  (void)inputs;
  FiguresWorkspace& fw = *ws.figures;
  for (std::size_t f = 0; f < model.figures.size(); ++f) {
    const FigureModel& figure = model.figures[f].model;
    const FigureDef& def = model.scene.figures[f];
    pbm::figure_kinematics(figure, q_of(figure, state.q), nullptr, fw.each[f]);
    segment_world_transforms(figure, fw.each[f], fw.world);
    for (int i = 0; i < figure.size(); ++i) {
      const SegmentShapeDef& shape = def.segments[i].shape;
      const Mat3 to_world = fw.world[i].E.transpose();
      draw::Primitive& p = snap.primitives.emplace_back();
      p.shape = primitive_of(shape.kind);
      p.center = (fw.world[i].r + to_world * shape.center).cast<float>();
      p.rotation = (to_world * rotation_from_quaternion(shape.orientation)).cast<float>();
      p.half_size = shape.size.cast<float>();
      p.material.color = def.segments[i].color.cast<float>();
      p.material.roughness = 0.6f;
      // The shape's bounding sphere frames an automatic camera.
      const float reach = static_cast<float>(shape.size.norm());
      snap.focus.add(p.center - draw::Vec3f::Constant(reach));
      snap.focus.add(p.center + draw::Vec3f::Constant(reach));
    }
  }
}

}  // namespace pbm::stages
