#include "app/render/render_target.h"

#include <utility>

namespace cb {

RenderTarget::~RenderTarget() {
  release();
}

RenderTarget::RenderTarget(RenderTarget&& o) noexcept {
  *this = std::move(o);
}

RenderTarget& RenderTarget::operator=(RenderTarget&& o) noexcept {
  if (this != &o) {
    release();
    std::swap(fbo_, o.fbo_);
    std::swap(texture_, o.texture_);
    std::swap(width_, o.width_);
    std::swap(height_, o.height_);
    std::swap(format_, o.format_);
  }
  return *this;
}

bool RenderTarget::create(int width, int height, Format format, std::string* error) {
  release();
  if (width <= 0 || height <= 0 || width > 16384 || height > 16384) {
    *error = "render target size " + std::to_string(width) + "x" + std::to_string(height) +
             " out of range 1..16384";
    return false;
  }
  glCreateTextures(GL_TEXTURE_2D, 1, &texture_);
  glTextureStorage2D(texture_, 1, format == Format::kRgba8 ? GL_RGBA8 : GL_RGBA32F, width, height);
  glTextureParameteri(texture_, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(texture_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(texture_, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(texture_, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glCreateFramebuffers(1, &fbo_);
  glNamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT0, texture_, 0);
  GLenum status = glCheckNamedFramebufferStatus(fbo_, GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    *error = "framebuffer incomplete (status 0x" + std::to_string(status) + ")";
    release();
    return false;
  }
  width_ = width;
  height_ = height;
  format_ = format;
  return true;
}

void RenderTarget::release() {
  if (fbo_) glDeleteFramebuffers(1, &fbo_);
  if (texture_) glDeleteTextures(1, &texture_);
  fbo_ = texture_ = 0;
  width_ = height_ = 0;
}

}  // namespace cb
