// 8-bit RGB PNG files for rendered frames and golden images (libpng).
#pragma once

#include <string>
#include <vector>

namespace pbm {

struct RgbImage {
  int width = 0, height = 0;
  std::vector<unsigned char> pixels;  // rows top to bottom, 3 bytes a pixel
};

// Writes through a temporary file renamed into place, so a failed write leaves nothing behind.
// zlib level 1: the default level costs more than rendering the frame (PLATFORM.md). Throws
// std::runtime_error naming the file.
void write_png(const std::string& path, const RgbImage& image, int compression_level = 1);

// Throws std::runtime_error naming the file if it is missing or not a PNG; converts to RGB.
RgbImage read_png(const std::string& path);

// Peak signal-to-noise ratio of b against a [dB] (infinity when equal); sizes must match.
double psnr(const RgbImage& a, const RgbImage& b);

}  // namespace pbm
