// Compiles a FigureDef into its FigureModel: parents by name (earlier segments, no cycle), joint
// frames from their sites, masses and inertias from the segments' geometry (sec. 15.1.1), and
// the initial q and v. Every refusal names the file and the JSON path of the field.
#pragma once

#include <string>

#include "figure/figure_def.h"
#include "figure/figure_model.h"

namespace pbm {

// Volume [m^3] of a shape, and its inertia (mass m, about its centre, in its own axes).
Real shape_volume(const SegmentShapeDef& shape);
Mat3 shape_inertia(const SegmentShapeDef& shape, Real m);

struct CompiledFigure {
  FigureModel model;
  VecX q0, v0;  // initial state, n_q and n_v
};

// `path` is the figure's JSON path ("figures[0]").
CompiledFigure build_figure_model(const FigureDef& def, const std::string& file,
                                  const std::string& path);

}  // namespace pbm
