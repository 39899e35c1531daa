// Draws the sky (sky_settings.h, shaders/sky.glsl) into the bound framebuffer before the cloud
// is composited over it. Owns the sky's textures: the LIC cloud layer (made on the CPU on first
// use, sky_lic.h, and kept while its settings stay the same) and the loaded image.
#pragma once

#include <map>
#include <memory>
#include <string>

#include "app/render/gl/gl.h"
#include "app/render/render_style.h"
#include "app/render/sky_settings.h"
#include "app/scene/camera.h"
#include "app/scene/light.h"

namespace cb {

class SkyPass {
 public:
  SkyPass() = default;
  ~SkyPass();
  SkyPass(const SkyPass&) = delete;
  SkyPass& operator=(const SkyPass&) = delete;

  // True when `style` shows `sky`: a sky kind other than none, and for the paper styles (ink,
  // sketch) only when their parameters ask for it (otherwise they keep their paper).
  static bool shows(const SkySettings& sky, RenderStyle style, const StyleParams& params);
  // Compiles the program render() will use for these settings (false with a message).
  bool prepare(const SkySettings& sky, RenderStyle style, std::string* error);
  // Fills the bound draw framebuffer's viewport (w×h pixels of a frame_w×frame_h frame; the
  // scissor as set by the caller) with the sky seen by `camera` under `light`.
  bool draw(const Camera& camera, int w, int h, int frame_w, int frame_h, const SkySettings& sky,
            RenderStyle style, const Light& light, std::string* error);

 private:
  GLuint program(const SkySettings& sky, RenderStyle style, std::string* error);
  void ensureLicTexture(const SkySettings& sky);
  void ensureImageTexture(const SkySettings& sky);

  std::map<std::string, GLuint> programs_;
  GLuint vao_ = 0;
  GLuint lic_texture_ = 0;
  std::string lic_key_;  // seed, size, length, coverage of lic_texture_
  GLuint image_texture_ = 0;
  const ImageRgba8* image_uploaded_ = nullptr;
  std::shared_ptr<const ImageRgba8> image_keep_;  // keeps image_uploaded_'s address unique
};

}  // namespace cb
