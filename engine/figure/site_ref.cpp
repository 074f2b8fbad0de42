#include "figure/site_ref.h"

#include "core/error.h"
#include "core/quaternion.h"

namespace pbm {

SiteRef find_site(const FigureDef& def, const FigureModel& figure, const std::string& segment,
                  const std::string& site, const std::string& file, const std::string& at) {
  SiteRef out;
  out.segment = -1;
  for (int i = 0; i < figure.size(); ++i) {
    if (figure.segments[i].name == segment) out.segment = i;
  }
  if (out.segment < 0) {
    throw Error(file, at + ".segment",
                "'" + segment + "' names no segment of figure '" + figure.name + "'");
  }
  if (site.empty()) return out;
  for (const SiteDef& s : def.segments[out.segment].sites) {
    if (s.name != site) continue;
    out.position = s.position;
    out.rotation = rotation_from_quaternion(s.orientation.normalized());
    return out;
  }
  throw Error(file, at + ".site", "'" + site + "' names no site of segment '" + segment + "'");
}

}  // namespace pbm
