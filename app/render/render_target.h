// An offscreen render target: a framebuffer object with one colour texture (RGBA8 for display
// and PNG, RGBA32F for EXR), and its readback. Needs a current GL context; move-only.
#pragma once

#include <string>

#include "app/render/gl/gl.h"
#include "app/render/image_io.h"

namespace cb {

class RenderTarget {
 public:
  enum class Format { kRgba8, kRgba32F };

  RenderTarget() = default;
  ~RenderTarget();
  RenderTarget(const RenderTarget&) = delete;
  RenderTarget& operator=(const RenderTarget&) = delete;
  RenderTarget(RenderTarget&& o) noexcept;
  RenderTarget& operator=(RenderTarget&& o) noexcept;

  // (Re)allocates for width×height; false with a message if the FBO is incomplete.
  bool create(int width, int height, Format format, std::string* error);
  void release();

  GLuint fbo() const { return fbo_; }
  GLuint texture() const { return texture_; }
  int width() const { return width_; }
  int height() const { return height_; }
  Format format() const { return format_; }

  ImageRgba8 readRgba8() const { return readFramebufferRgba8(fbo_, width_, height_); }
  ImageRgbaF readRgbaF() const { return readFramebufferRgbaF(fbo_, width_, height_); }

 private:
  GLuint fbo_ = 0, texture_ = 0;
  int width_ = 0, height_ = 0;
  Format format_ = Format::kRgba8;
};

}  // namespace cb
