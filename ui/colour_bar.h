// What a field section looks like (draw::FieldSection): its false colours, and the colour bar that
// names it, drawn over the picture. Plain geometry for the renderer's coloured pass: no GL here.
#pragma once

#include <vector>

#include "draw/snapshot.h"

namespace pbm {

// The false colour of t in [0, 1] (clamped): viridis (van der Walt and Smith, matplotlib's
// default), perceptually uniform and readable in grey, as display RGB.
Eigen::Vector3f section_colour(float t);

// Appends the section's cells as triangles (x, y, z, r, g, b per vertex, world positions), one
// flat colour per sample; NaN samples are left out.
void append_section_triangles(const draw::FieldSection& section, std::vector<float>& vertices);

// Appends the section's colour bar as triangles (x, y, 0, r, g, b per vertex) in pixels from the
// image's top-right corner, x negative to the left, y down: a dark panel, the gradient from low
// (bottom) to high (top), and the label and the range's ends in a bitmap font (stb_easy_font).
// Bar `slot` k stands k panels to the left of the first; a panel is 240 pixels wide.
void append_colour_bar(const draw::FieldSection& section, int slot, std::vector<float>& vertices);

}  // namespace pbm
