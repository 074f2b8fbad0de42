// A scatter plot on log-log axes written as a PNG (`pbm bench tradeoff`): points by series, a
// polyline through marked points, one highlighted point, decade grid lines and their labels,
// a title and a legend. Text is drawn from Dear ImGui's embedded font atlas, built in memory (no
// GL context, no font file).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "png_io.h"

namespace pbm {

struct PlotSeries {
  std::string name;
  std::array<unsigned char, 3> color{0, 0, 0};
  std::vector<std::array<double, 2>> points;  // (x, y), both > 0
  std::vector<double> radii;                  // marker radius [px] of each point (empty: 4.5)
};

struct LogLogPlot {
  std::string title, x_label, y_label;
  std::vector<PlotSeries> series;
  std::string line_name;                         // legend entry of the polyline
  std::vector<std::array<double, 2>> line;       // drawn in order
  std::string highlight_name;                    // legend entry of the highlighted point
  std::vector<std::array<double, 2>> highlight;  // ringed in red
  std::string size_note;                         // legend line saying what marker size means
  int width = 1000, height = 680;
};

RgbImage render_plot(const LogLogPlot& plot);

}  // namespace pbm
