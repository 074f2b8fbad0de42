#include "colour_bar.h"

#include <stb/stb_easy_font.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

namespace pbm {
namespace {

using Vec3f = Eigen::Vector3f;

// viridis at 0, 1/8, ..., 1 (display RGB: its nine-step palette #440154 ... #fde725), linearly
// interpolated between.
constexpr std::array<std::array<float, 3>, 9> kViridis{{{0.267f, 0.004f, 0.329f},
                                                        {0.278f, 0.176f, 0.482f},
                                                        {0.231f, 0.322f, 0.545f},
                                                        {0.173f, 0.447f, 0.557f},
                                                        {0.129f, 0.569f, 0.549f},
                                                        {0.157f, 0.682f, 0.502f},
                                                        {0.369f, 0.788f, 0.384f},
                                                        {0.678f, 0.863f, 0.188f},
                                                        {0.992f, 0.906f, 0.145f}}};

// Bar geometry [pixels].
constexpr float kMargin = 12, kPanelWidth = 240, kBarWidth = 18, kBarHeight = 180, kPad = 8;
constexpr float kTextScale = 2;  // stb_easy_font's glyphs are 7 pixels tall
constexpr int kGradientSteps = 32;

void vertex(std::vector<float>& out, float x, float y, float z, const Vec3f& c) {
  out.insert(out.end(), {x, y, z, c.x(), c.y(), c.z()});
}

void quad(std::vector<float>& out, float x0, float y0, float x1, float y1, const Vec3f& c0,
          const Vec3f& c1) {  // c0 along y0, c1 along y1
  vertex(out, x0, y0, 0, c0);
  vertex(out, x1, y0, 0, c0);
  vertex(out, x1, y1, 0, c1);
  vertex(out, x0, y0, 0, c0);
  vertex(out, x1, y1, 0, c1);
  vertex(out, x0, y1, 0, c1);
}

// Text at (x, y) (its top left) in white, scaled.
void text(std::vector<float>& out, float x, float y, const std::string& s) {
  // stb_easy_font's vertices: x, y, z (float) and a colour (4 bytes); ~270 bytes a character.
  struct Glyph {
    float x, y, z;
    unsigned char rgba[4];
  };
  std::vector<Glyph> quads(s.size() * 300 / sizeof(Glyph) + 16);
  std::string copy = s;
  const int n = stb_easy_font_print(0, 0, copy.data(), nullptr, quads.data(),
                                    static_cast<int>(quads.size() * sizeof(Glyph)));
  const Vec3f white = Vec3f::Ones();
  for (int q = 0; q < n; ++q) {
    const Glyph* g = &quads[static_cast<std::size_t>(4 * q)];
    for (int k : {0, 1, 2, 0, 2, 3}) {
      vertex(out, x + kTextScale * g[k].x, y + kTextScale * g[k].y, 0, white);
    }
  }
}

float text_width(const std::string& s) {
  std::string copy = s;
  return kTextScale * static_cast<float>(stb_easy_font_width(copy.data()));
}

std::string number(float x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", static_cast<double>(x));
  return buffer;
}

}  // namespace

Vec3f section_colour(float t) {
  if (!(t > 0)) t = 0;  // NaN too
  t = std::min(t, 1.0f);
  const float x = t * 8;
  const int k = std::min(static_cast<int>(x), 7);
  const float f = x - static_cast<float>(k);
  const std::array<float, 3>& a = kViridis[static_cast<std::size_t>(k)];
  const std::array<float, 3>& b = kViridis[static_cast<std::size_t>(k + 1)];
  return {a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1]), a[2] + f * (b[2] - a[2])};
}

void append_section_triangles(const draw::FieldSection& s, std::vector<float>& out) {
  if (s.nu <= 0 || s.nv <= 0 || s.values.size() < static_cast<std::size_t>(s.nu) * s.nv) return;
  const float span = s.high > s.low ? s.high - s.low : 1.0f;
  const Vec3f du = s.u / static_cast<float>(s.nu), dv = s.v / static_cast<float>(s.nv);
  for (int j = 0; j < s.nv; ++j) {
    for (int i = 0; i < s.nu; ++i) {
      const float value = s.values[static_cast<std::size_t>(i + s.nu * j)];
      if (!std::isfinite(value)) continue;
      const Vec3f c = section_colour((value - s.low) / span);
      const Vec3f p00 = s.corner + static_cast<float>(i) * du + static_cast<float>(j) * dv;
      const Vec3f p10 = p00 + du, p11 = p00 + du + dv, p01 = p00 + dv;
      for (const Vec3f* p : {&p00, &p10, &p11, &p00, &p11, &p01}) {
        vertex(out, p->x(), p->y(), p->z(), c);
      }
    }
  }
}

void append_colour_bar(const draw::FieldSection& s, int slot, std::vector<float>& out) {
  const float right = -kMargin - static_cast<float>(slot) * (kPanelWidth + kMargin);
  const float left = right - kPanelWidth;
  const float top = kMargin;
  const float line = 7 * kTextScale + 6;
  const float bar_top = top + kPad + line, bar_bottom = bar_top + kBarHeight;
  const float bottom = bar_bottom + kPad;
  quad(out, left, top, right, bottom, Vec3f::Constant(0.12f), Vec3f::Constant(0.12f));
  const float bar_left = left + kPad, bar_right = bar_left + kBarWidth;
  for (int k = 0; k < kGradientSteps; ++k) {
    const float t0 = static_cast<float>(k) / kGradientSteps;
    const float t1 = static_cast<float>(k + 1) / kGradientSteps;
    // Up the bar: y falls as t rises.
    quad(out, bar_left, bar_bottom - t0 * kBarHeight, bar_right, bar_bottom - t1 * kBarHeight,
         section_colour(t0), section_colour(t1));
  }
  // The label across the panel's top (cut to fit), the range's ends beside the bar.
  std::string label = s.label;
  while (label.size() > 1 && text_width(label) > kPanelWidth - 2 * kPad) label.pop_back();
  text(out, left + kPad, top + kPad, label);
  const float x = bar_right + kPad;
  text(out, x, bar_top, number(s.high));
  text(out, x, 0.5f * (bar_top + bar_bottom) - 0.5f * line, number(0.5f * (s.low + s.high)));
  text(out, x, bar_bottom - line + 6, number(s.low));
}

}  // namespace pbm
