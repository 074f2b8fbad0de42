// A cross-section of a liquid's grid for display (LiquidDef::section): the pressure [Pa] or the
// speed [m/s] at the centres of one layer of cells across an axis, NaN where the cell holds no
// liquid, with the colour bar's range from 0 to the largest value in the section.
#pragma once

#include <optional>
#include <vector>

#include "draw/snapshot.h"
#include "liquid/liquid_state.h"

namespace pbm {

// The section LiquidDef::section asks for, from the cells labelled in `flags` (cell_labels.h);
// none when it asks for none. A 2D grid's section across its thin axis is its whole plane.
std::optional<draw::FieldSection> liquid_section(const LiquidModel& model, const LiquidState& state,
                                                 const std::vector<CellFlag>& flags);

}  // namespace pbm
