#include "png_io.h"

#include <png.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <stdexcept>

namespace pbm {
namespace {

struct FileCloser {
  void operator()(std::FILE* f) const {
    if (f != nullptr) std::fclose(f);
  }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

[[noreturn]] void png_fail(png_structp png, png_const_charp message) {
  auto* what = static_cast<std::string*>(png_get_error_ptr(png));
  if (what != nullptr) *what = message;
  png_longjmp(png, 1);
}

}  // namespace

void write_png(const std::string& path, const RgbImage& image, int compression_level) {
  const std::string temporary = path + ".partial";
  std::string error;
  {
    File file(std::fopen(temporary.c_str(), "wb"));
    if (!file) throw std::runtime_error(path + ": cannot write");
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &error, &png_fail, nullptr);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (png == nullptr || info == nullptr) throw std::runtime_error(path + ": out of memory");
    if (setjmp(png_jmpbuf(png))) {
      png_destroy_write_struct(&png, &info);
      file.reset();
      std::filesystem::remove(temporary);
      throw std::runtime_error(path + ": " + error);
    }
    png_init_io(png, file.get());
    png_set_compression_level(png, compression_level);
    png_set_IHDR(png, info, static_cast<png_uint_32>(image.width),
                 static_cast<png_uint_32>(image.height), 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    for (int y = 0; y < image.height; ++y) {
      png_write_row(png, image.pixels.data() + 3 * static_cast<std::size_t>(y) * image.width);
    }
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    if (std::fflush(file.get()) != 0) {
      file.reset();
      std::filesystem::remove(temporary);
      throw std::runtime_error(path + ": write failed (disk full?)");
    }
  }
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  if (ec) {
    std::filesystem::remove(temporary);
    throw std::runtime_error(path + ": cannot rename into place: " + ec.message());
  }
}

RgbImage read_png(const std::string& path) {
  File file(std::fopen(path.c_str(), "rb"));
  if (!file) throw std::runtime_error(path + ": cannot open");
  unsigned char signature[8] = {};
  if (std::fread(signature, 1, 8, file.get()) != 8 || png_sig_cmp(signature, 0, 8) != 0) {
    throw std::runtime_error(path + ": not a PNG file");
  }
  std::string error;
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &error, &png_fail, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (png == nullptr || info == nullptr) throw std::runtime_error(path + ": out of memory");
  RgbImage image;
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    throw std::runtime_error(path + ": " + error);
  }
  png_init_io(png, file.get());
  png_set_sig_bytes(png, 8);
  png_read_info(png, info);
  png_set_expand(png);
  png_set_strip_16(png);
  png_set_strip_alpha(png);
  png_set_gray_to_rgb(png);
  png_read_update_info(png, info);
  image.width = static_cast<int>(png_get_image_width(png, info));
  image.height = static_cast<int>(png_get_image_height(png, info));
  image.pixels.resize(3 * static_cast<std::size_t>(image.width) * image.height);
  for (int y = 0; y < image.height; ++y) {
    png_read_row(png, image.pixels.data() + 3 * static_cast<std::size_t>(y) * image.width, nullptr);
  }
  png_destroy_read_struct(&png, &info, nullptr);
  return image;
}

double psnr(const RgbImage& a, const RgbImage& b) {
  if (a.width != b.width || a.height != b.height) {
    throw std::runtime_error("PSNR of images of different sizes");
  }
  double sum = 0;
  for (std::size_t k = 0; k < a.pixels.size(); ++k) {
    const double d = static_cast<double>(a.pixels[k]) - b.pixels[k];
    sum += d * d;
  }
  if (sum == 0) return std::numeric_limits<double>::infinity();
  const double mse = sum / static_cast<double>(a.pixels.size());
  return 10.0 * std::log10(255.0 * 255.0 / mse);
}

}  // namespace pbm
