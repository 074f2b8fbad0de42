// A site named in a scene (sec. 15.1.1: attachment frames on segments), resolved to its segment
// and its frame there, for the figure's events and actuators that act at sites.
#pragma once

#include <string>

#include "core/types.h"
#include "figure/figure_def.h"
#include "figure/figure_model.h"

namespace pbm {

struct SiteRef {
  int segment = 0;
  Vec3 position = Vec3::Zero();      // in the segment's frame [m]
  Mat3 rotation = Mat3::Identity();  // site axes -> segment axes
};

// The site `site` of the segment named `segment` (an empty site: the segment's frame origin, its
// root site). Refuses a segment or site that does not exist with pbm::Error at `at` + ".segment"
// or ".site" (`at`: the JSON path of the item that names them).
SiteRef find_site(const FigureDef& def, const FigureModel& figure, const std::string& segment,
                  const std::string& site, const std::string& file, const std::string& at);

}  // namespace pbm
