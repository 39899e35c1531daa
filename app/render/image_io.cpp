#include "app/render/image_io.h"

#include <algorithm>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <memory>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <png.h>

#include "app/core/atomic_file.h"

namespace cb {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw ImageIoError("image file '" + path + "': " + what);
}

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;

void checkImage(const std::string& path, int width, int height, size_t values) {
  if (width <= 0 || height <= 0 || values != size_t(width) * height * 4)
    fail(path,
         "image has inconsistent size " + std::to_string(width) + "x" + std::to_string(height));
}

bool endsWith(const std::string& s, const std::string& suffix) {
  if (s.size() < suffix.size()) return false;
  return std::equal(suffix.rbegin(), suffix.rend(), s.rbegin(),
                    [](char a, char b) { return std::tolower(a) == b; });
}

// Every image is written to a temporary beside `path` and renamed over it once on the disk
// (app/core/atomic_file.h): a full disk or a crash never leaves a torn picture.
void commitImage(AtomicFileReplacement& out) {
  std::string error;
  if (!out.commit(&error)) fail(out.path(), error);
}

void writePngFile(const std::string& path, const ImageRgba8& image) {
  FilePtr f(std::fopen(path.c_str(), "wb"));
  if (!f) fail(path, std::string("cannot open for writing: ") + std::strerror(errno));
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    fail(path, "libpng could not start");
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    fail(path, "libpng failed while writing");
  }
  png_init_io(png, f.get());
  png_set_IHDR(png, info, png_uint_32(image.width), png_uint_32(image.height), 8,
               PNG_COLOR_TYPE_RGBA, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < image.height; ++y) png_write_row(png, const_cast<png_bytep>(image.at(0, y)));
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  if (std::fflush(f.get()) != 0 || std::ferror(f.get()))
    fail(path, std::string("write failed: ") + std::strerror(errno));
  if (std::fclose(f.release()) != 0)
    fail(path, std::string("write failed: ") + std::strerror(errno));
}

// The 256 most frequent 5-bit-per-channel bins (ties: the lower bin), each as its pixels' mean.
std::vector<png_color> popularPalette(const ImageRgba8& image) {
  std::vector<uint32_t> count(1 << 15), sum(3 << 15);
  auto bin = [](const uint8_t* p) { return (p[0] >> 3) << 10 | (p[1] >> 3) << 5 | (p[2] >> 3); };
  for (size_t i = 0; i < image.pixels.size(); i += 4) {
    const int b = bin(&image.pixels[i]);
    ++count[size_t(b)];
    for (int c = 0; c < 3; ++c) sum[size_t(b) * 3 + size_t(c)] += image.pixels[i + size_t(c)];
  }
  std::vector<int> bins;
  for (int b = 0; b < (1 << 15); ++b)
    if (count[size_t(b)]) bins.push_back(b);
  std::stable_sort(bins.begin(), bins.end(),
                   [&](int a, int b) { return count[size_t(a)] > count[size_t(b)]; });
  bins.resize(std::min<size_t>(bins.size(), 256));
  std::vector<png_color> palette;
  for (int b : bins) {
    const uint32_t n = count[size_t(b)], *m = &sum[size_t(b) * 3];
    palette.push_back(
        {png_byte((m[0] + n / 2) / n), png_byte((m[1] + n / 2) / n), png_byte((m[2] + n / 2) / n)});
  }
  return palette;
}

// Each pixel as the index of its nearest palette colour (squared RGB distance; first on ties).
std::vector<png_byte> paletteIndices(const ImageRgba8& image,
                                     const std::vector<png_color>& palette) {
  std::vector<png_byte> out(size_t(image.width) * size_t(image.height));
  for (size_t i = 0; i < out.size(); ++i) {
    const uint8_t* p = &image.pixels[i * 4];
    int best = 0, best_d = 1 << 30;
    for (size_t k = 0; k < palette.size(); ++k) {
      const int dr = p[0] - palette[k].red, dg = p[1] - palette[k].green,
                db = p[2] - palette[k].blue, d = dr * dr + dg * dg + db * db;
      if (d < best_d) best_d = d, best = int(k);
    }
    out[i] = png_byte(best);
  }
  return out;
}

void writePngPaletteFile(const std::string& path, const ImageRgba8& image) {
  const std::vector<png_color> palette = popularPalette(image);
  const std::vector<png_byte> indices = paletteIndices(image, palette);
  FilePtr f(std::fopen(path.c_str(), "wb"));
  if (!f) fail(path, std::string("cannot open for writing: ") + std::strerror(errno));
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    fail(path, "libpng could not start");
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    fail(path, "libpng failed while writing");
  }
  png_init_io(png, f.get());
  png_set_compression_level(png, 9);
  png_set_IHDR(png, info, png_uint_32(image.width), png_uint_32(image.height), 8,
               PNG_COLOR_TYPE_PALETTE, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_set_PLTE(png, info, palette.data(), int(palette.size()));
  png_write_info(png, info);
  for (int y = 0; y < image.height; ++y)
    png_write_row(png, &indices[size_t(y) * size_t(image.width)]);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  if (std::fflush(f.get()) != 0 || std::ferror(f.get()))
    fail(path, std::string("write failed: ") + std::strerror(errno));
  if (std::fclose(f.release()) != 0)
    fail(path, std::string("write failed: ") + std::strerror(errno));
}

}  // namespace

void writePngPalette(const std::string& path, const ImageRgba8& image) {
  checkImage(path, image.width, image.height, image.pixels.size());
  AtomicFileReplacement out(path);
  writePngPaletteFile(out.tempPath(), image);
  commitImage(out);
}

void writePng(const std::string& path, const ImageRgba8& image) {
  checkImage(path, image.width, image.height, image.pixels.size());
  AtomicFileReplacement out(path);
  writePngFile(out.tempPath(), image);
  commitImage(out);
}

ImageRgba8 readPng(const std::string& path, int64_t max_pixels) {
  png_image img;
  std::memset(&img, 0, sizeof img);
  img.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&img, path.c_str()))
    fail(path, std::string("cannot read PNG: ") + img.message);
  // Only the header has been read: refuse an image too large before allocating for it.
  if (max_pixels > 0 && int64_t(img.width) * int64_t(img.height) > max_pixels) {
    png_image_free(&img);
    fail(path, "PNG is " + std::to_string(img.width) + "x" + std::to_string(img.height) +
                   ", more than the " + std::to_string(max_pixels) + " pixels allowed here");
  }
  img.format = PNG_FORMAT_RGBA;
  if (img.width > kMaxPngSide || img.height > kMaxPngSide) {
    png_image_free(&img);
    fail(path, "header field IHDR claims " + std::to_string(img.width) + "x" +
                   std::to_string(img.height) + " pixels; at most " + std::to_string(kMaxPngSide) +
                   " per side are read");
  }
  ImageRgba8 out;
  out.width = int(img.width);
  out.height = int(img.height);
  out.pixels.resize(PNG_IMAGE_SIZE(img));
  if (!png_image_finish_read(&img, nullptr, out.pixels.data(), 0, nullptr))
    fail(path, std::string("cannot decode PNG: ") + img.message);
  return out;
}

void writeExr(const std::string& path, const ImageRgbaF& image) {
  checkImage(path, image.width, image.height, image.pixels.size());
  AtomicFileReplacement out(path);
  try {
    Imf::Header header(image.width, image.height);
    header.compression() = Imf::ZIP_COMPRESSION;
    const char* names[4] = {"R", "G", "B", "A"};
    for (const char* n : names) header.channels().insert(n, Imf::Channel(Imf::FLOAT));
    Imf::OutputFile file(out.tempPath().c_str(), header);
    Imf::FrameBuffer fb;
    char* base = reinterpret_cast<char*>(const_cast<float*>(image.pixels.data()));
    for (int c = 0; c < 4; ++c)
      fb.insert(names[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), 4 * sizeof(float),
                                     4 * sizeof(float) * size_t(image.width)));
    file.setFrameBuffer(fb);
    file.writePixels(image.height);
  } catch (const std::exception& e) {
    fail(path, std::string("OpenEXR: ") + e.what());
  }  // the OutputFile is closed (flushed) here, before the commit
  commitImage(out);
}

void writeImageByExtension(const std::string& path, const ImageRgba8& rgba8,
                           const ImageRgbaF& rgbaf) {
  if (endsWith(path, ".png"))
    writePng(path, rgba8);
  else if (endsWith(path, ".exr"))
    writeExr(path, rgbaf);
  else
    fail(path, "unknown image type (use .png or .exr)");
}

namespace {

// GL rows run bottom-up; images here run top-down (4 channels per pixel).
template <typename T>
void flipRowsToTopDown(std::vector<T>* pixels, int width, int height) {
  const size_t row = size_t(width) * 4;
  for (int y = 0; y < height / 2; ++y)
    std::swap_ranges(pixels->begin() + y * row, pixels->begin() + (y + 1) * row,
                     pixels->begin() + (height - 1 - y) * row);
}

}  // namespace

namespace {

// The framebuffer's colour as `Image` (RGBA of `type`), rows top-down.
template <class Image>
Image readFramebuffer(GLuint fbo, int width, int height, GLenum type, int alignment) {
  Image out;
  out.width = width;
  out.height = height;
  out.pixels.resize(size_t(width) * height * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
  glPixelStorei(GL_PACK_ALIGNMENT, alignment);
  glReadPixels(0, 0, width, height, GL_RGBA, type, out.pixels.data());
  flipRowsToTopDown(&out.pixels, width, height);
  return out;
}

}  // namespace

ImageRgba8 readFramebufferRgba8(GLuint fbo, int width, int height) {
  return readFramebuffer<ImageRgba8>(fbo, width, height, GL_UNSIGNED_BYTE, 1);
}

ImageRgbaF readFramebufferRgbaF(GLuint fbo, int width, int height) {
  return readFramebuffer<ImageRgbaF>(fbo, width, height, GL_FLOAT, 4);
}

}  // namespace cb
