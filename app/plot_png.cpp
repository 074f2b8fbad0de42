#include "plot_png.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace pbm {
namespace {

using Color = std::array<unsigned char, 3>;

struct Canvas {
  RgbImage image;
  Canvas(int w, int h) {
    image.width = w;
    image.height = h;
    image.pixels.assign(static_cast<std::size_t>(3 * w * h), 255);
  }
  void blend(int x, int y, const Color& c, double alpha) {
    if (x < 0 || y < 0 || x >= image.width || y >= image.height || alpha <= 0) return;
    unsigned char* p = &image.pixels[static_cast<std::size_t>(3 * (y * image.width + x))];
    for (int k = 0; k < 3; ++k) {
      p[k] = static_cast<unsigned char>(std::lround(p[k] + (c[k] - p[k]) * std::min(alpha, 1.0)));
    }
  }
  void disc(double cx, double cy, double r, const Color& c) {
    for (int y = static_cast<int>(cy - r - 1); y <= static_cast<int>(cy + r + 1); ++y)
      for (int x = static_cast<int>(cx - r - 1); x <= static_cast<int>(cx + r + 1); ++x) {
        const double d = std::hypot(x + 0.5 - cx, y + 0.5 - cy);
        blend(x, y, c, r + 0.5 - d);  // a half-pixel soft edge
      }
  }
  void ring(double cx, double cy, double r, double width, const Color& c) {
    for (int y = static_cast<int>(cy - r - width); y <= static_cast<int>(cy + r + width); ++y)
      for (int x = static_cast<int>(cx - r - width); x <= static_cast<int>(cx + r + width); ++x) {
        const double d = std::abs(std::hypot(x + 0.5 - cx, y + 0.5 - cy) - r);
        blend(x, y, c, 0.5 * width + 0.5 - d);
      }
  }
  void line(double x0, double y0, double x1, double y1, double width, const Color& c) {
    const double length = std::hypot(x1 - x0, y1 - y0);
    const int steps = std::max(1, static_cast<int>(length * 2));
    for (int i = 0; i <= steps; ++i) {
      const double t = static_cast<double>(i) / steps;
      disc(x0 + t * (x1 - x0), y0 + t * (y1 - y0), 0.5 * width, c);
    }
  }
};

// Dear ImGui's embedded font (ProggyClean, 13 px), rasterized once into an alpha atlas.
class Font {
 public:
  Font() {
    font_ = atlas_.AddFontDefault();
    atlas_.GetTexDataAsAlpha8(&pixels_, &width_, &height_);
  }
  double text_width(const std::string& text) const {
    double w = 0;
    for (char ch : text) w += font_->FindGlyph(static_cast<ImWchar>(ch))->AdvanceX;
    return w;
  }
  double line_height() const { return font_->FontSize; }
  // Draws text with its top-left corner at (x, y).
  void draw(Canvas& canvas, double x, double y, const std::string& text, const Color& c) const {
    for (char ch : text) {
      const ImFontGlyph* g = font_->FindGlyph(static_cast<ImWchar>(ch));
      const int u0 = static_cast<int>(std::lround(g->U0 * width_));
      const int v0 = static_cast<int>(std::lround(g->V0 * height_));
      const int gw = static_cast<int>(std::lround((g->U1 - g->U0) * width_));
      const int gh = static_cast<int>(std::lround((g->V1 - g->V0) * height_));
      for (int j = 0; j < gh; ++j)
        for (int i = 0; i < gw; ++i) {
          const double a = pixels_[(v0 + j) * width_ + u0 + i] / 255.0;
          canvas.blend(static_cast<int>(std::lround(x + g->X0)) + i,
                       static_cast<int>(std::lround(y + g->Y0)) + j, c, a);
        }
      x += g->AdvanceX;
    }
  }

 private:
  ImFontAtlas atlas_;
  ImFont* font_ = nullptr;
  unsigned char* pixels_ = nullptr;
  int width_ = 0, height_ = 0;
};

std::string decade_label(int e) {
  char text[16];
  if (e >= -2 && e <= 2) {
    std::snprintf(text, sizeof text, "%g", std::pow(10.0, e));
  } else {
    std::snprintf(text, sizeof text, "1e%d", e);
  }
  return text;
}

}  // namespace

RgbImage render_plot(const LogLogPlot& plot) {
  Canvas canvas(plot.width, plot.height);
  const Font font;
  const Color black{0, 0, 0}, grid{225, 225, 225}, axis{90, 90, 90}, red{220, 30, 30};
  const double left = 80, right = plot.width - 200.0, top = 50, bottom = plot.height - 60.0;
  // Ranges: whole decades around every point.
  double lo[2] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  double hi[2] = {-lo[0], -lo[1]};
  auto extend = [&](const std::array<double, 2>& p) {
    for (int a = 0; a < 2; ++a) {
      if (!(p[a] > 0)) continue;
      lo[a] = std::min(lo[a], std::log10(p[a]));
      hi[a] = std::max(hi[a], std::log10(p[a]));
    }
  };
  for (const PlotSeries& s : plot.series)
    for (const auto& p : s.points) extend(p);
  for (int a = 0; a < 2; ++a) {
    if (!std::isfinite(lo[a])) lo[a] = hi[a] = 0;
    lo[a] = std::floor(lo[a]);
    hi[a] = std::max(std::ceil(hi[a]), lo[a] + 1);
  }
  auto X = [&](double x) {
    return left + (std::log10(x) - lo[0]) / (hi[0] - lo[0]) * (right - left);
  };
  auto Y = [&](double y) {
    return bottom - (std::log10(std::max(y, 1e-300)) - lo[1]) / (hi[1] - lo[1]) * (bottom - top);
  };
  // Grid and decade labels.
  for (int e = static_cast<int>(lo[0]); e <= static_cast<int>(hi[0]); ++e) {
    const double x = X(std::pow(10.0, e));
    canvas.line(x, top, x, bottom, 1, grid);
    const std::string label = decade_label(e);
    font.draw(canvas, x - 0.5 * font.text_width(label), bottom + 8, label, black);
  }
  for (int e = static_cast<int>(lo[1]); e <= static_cast<int>(hi[1]); ++e) {
    const double y = Y(std::pow(10.0, e));
    canvas.line(left, y, right, y, 1, grid);
    const std::string label = decade_label(e);
    font.draw(canvas, left - 8 - font.text_width(label), y - 0.5 * font.line_height(), label,
              black);
  }
  canvas.line(left, bottom, right, bottom, 1.5, axis);
  canvas.line(left, top, left, bottom, 1.5, axis);
  font.draw(canvas, left, 12, plot.title, black);
  font.draw(canvas, 0.5 * (left + right) - 0.5 * font.text_width(plot.x_label), bottom + 32,
            plot.x_label, black);
  font.draw(canvas, left, top - 18, plot.y_label, black);
  // The polyline, the points, the highlight.
  for (std::size_t i = 1; i < plot.line.size(); ++i) {
    canvas.line(X(plot.line[i - 1][0]), Y(plot.line[i - 1][1]), X(plot.line[i][0]),
                Y(plot.line[i][1]), 2, black);
  }
  for (const PlotSeries& s : plot.series)
    for (std::size_t i = 0; i < s.points.size(); ++i) {
      const double r = i < s.radii.size() ? s.radii[i] : 4.5;
      canvas.disc(X(s.points[i][0]), Y(s.points[i][1]), r, s.color);
    }
  for (const auto& p : plot.highlight) canvas.ring(X(p[0]), Y(p[1]), 9, 2.5, red);
  // Legend.
  double ly = top;
  const double lx = right + 20;
  for (const PlotSeries& s : plot.series) {
    canvas.disc(lx + 6, ly + 7, 4.5, s.color);
    font.draw(canvas, lx + 18, ly, s.name, black);
    ly += 20;
  }
  if (!plot.line_name.empty()) {
    canvas.line(lx, ly + 7, lx + 12, ly + 7, 2, black);
    font.draw(canvas, lx + 18, ly, plot.line_name, black);
    ly += 20;
  }
  if (!plot.highlight_name.empty()) {
    canvas.ring(lx + 6, ly + 7, 7, 2.5, red);
    font.draw(canvas, lx + 18, ly, plot.highlight_name, black);
    ly += 20;
  }
  if (!plot.size_note.empty()) font.draw(canvas, lx, ly, plot.size_note, black);
  return canvas.image;
}

}  // namespace pbm
