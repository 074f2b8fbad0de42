// The Dear ImGui panels of the studio (issue: outliner, inspector, transport, timeline, stats).
// They read the Studio and act through StudioActions and the runner's commands; no Qt here.
#pragma once

#include "studio.h"

namespace pbm {

void draw_panels(Studio& studio, StudioActions& actions, float width, float height);

}  // namespace pbm
