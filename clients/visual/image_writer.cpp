#include "clients/visual/image_writer.hpp"

#include <png.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>

#include "base/error.hpp"

namespace thx::visual {
namespace {

using File = std::unique_ptr<std::FILE, int (*)(std::FILE*)>;

File openForWriting(const std::string& path) {
  File f(std::fopen(path.c_str(), "wb"), &std::fclose);
  if (!f) throw Error(Error::Kind::Io, path + ": cannot write (" + std::strerror(errno) + ")");
  return f;
}

void writePpm(const std::string& path, const Rgba8Image& image) {
  File f = openForWriting(path);
  std::fprintf(f.get(), "P6\n%d %d\n255\n", image.width, image.height);
  std::vector<std::uint8_t> rgb(std::size_t(image.width) * image.height * 3);
  for (std::size_t p = 0; p < std::size_t(image.width) * image.height; ++p)
    std::memcpy(&rgb[p * 3], &image.rgba[p * 4], 3);
  if (std::fwrite(rgb.data(), 1, rgb.size(), f.get()) != rgb.size())
    throw Error(Error::Kind::Io, path + ": write failed (" + std::strerror(errno) + ")");
}

void writePng(const std::string& path, const Rgba8Image& image, int level) {
  File f = openForWriting(path);
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    throw Error(Error::Kind::Io, path + ": libpng could not start");
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    throw Error(Error::Kind::Io, path + ": libpng failed while writing");
  }
  png_init_io(png, f.get());
  png_set_compression_level(png, level);
  // Row filters pay off only when the file is kept small on purpose.
  if (level <= 1) png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_NONE);
  png_set_IHDR(png, info, png_uint_32(image.width), png_uint_32(image.height), 8, PNG_COLOR_TYPE_RGB_ALPHA,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < image.height; ++y)
    png_write_row(png, image.rgba.data() + std::size_t(y) * image.width * 4);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
}

}  // namespace

void writeImage(const std::string& path, const Rgba8Image& image, int png_level) {
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext == ".png") writePng(path, image, png_level);
  else if (ext == ".ppm") writePpm(path, image);
  else throw UsageError(path + ": unknown image type '" + ext + "'; expected .png or .ppm");
}

std::string framePath(const std::string& dir, int index, const std::string& format) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%04d.", index);
  return (std::filesystem::path(dir) / (name + format)).string();
}

}  // namespace thx::visual
