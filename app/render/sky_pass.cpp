#include "app/render/sky_pass.h"

#include <chrono>
#include <cstdio>

#include <glm/gtc/type_ptr.hpp>

#include "app/render/shader_program.h"
#include "app/render/sky_function.h"
#include "app/render/sky_lic.h"

namespace cb {

SkyPass::~SkyPass() {
  for (auto& [key, p] : programs_) glDeleteProgram(p);
  if (vao_) glDeleteVertexArrays(1, &vao_);
  if (lic_texture_) glDeleteTextures(1, &lic_texture_);
  if (image_texture_) glDeleteTextures(1, &image_texture_);
}

bool SkyPass::shows(const SkySettings& sky, RenderStyle style, const StyleParams& params) {
  if (sky.kind == SkyKind::kNone) return false;
  if (sky.kind == SkyKind::kImage && !sky.image) return false;
  const RenderStyleRow& row = renderStyleRow(style);
  return !row.shows_sky || row.shows_sky(params);
}

GLuint SkyPass::program(const SkySettings& sky, RenderStyle style, std::string* error) {
  const std::string defines = "#define CB_SKY_KIND " + std::to_string(int(sky.kind)) +
                              "\n#define CB_SKY_POSTERISE " +
                              (renderStyleRow(style).posterised_sky ? "1" : "0") + "\n";
  auto it = programs_.find(defines);
  if (it != programs_.end()) return it->second;
  GLuint p = linkProgram({"fullscreen.vert.glsl"}, {"sky.glsl", "sky.frag.glsl"}, error, defines);
  if (p) programs_[defines] = p;
  return p;
}

bool SkyPass::prepare(const SkySettings& sky, RenderStyle style, std::string* error) {
  return sky.kind == SkyKind::kNone || program(sky, style, error) != 0;
}

void SkyPass::ensureLicTexture(const SkySettings& sky) {
  const std::string key = std::to_string(sky.lic_seed) + "/" + std::to_string(sky.lic_size) + "/" +
                          std::to_string(sky.lic_length) + "/" + std::to_string(sky.lic_coverage);
  if (lic_texture_ && key == lic_key_) return;
  if (lic_texture_) glDeleteTextures(1, &lic_texture_);
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<uint8_t> texels =
      makeLicSkyTexture(sky.lic_size, sky.lic_length, sky.lic_coverage, sky.lic_seed);
  // Once per run (seconds at 512² on a loaded 2-core machine): say what the first frame waited for.
  std::fprintf(
      stderr, "cloudbrush: made the LIC sky texture (%d², streaks %d texels) in %.0f ms\n",
      sky.lic_size, sky.lic_length,
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  int levels = 1;
  while ((sky.lic_size >> levels) > 0) ++levels;
  glCreateTextures(GL_TEXTURE_2D, 1, &lic_texture_);
  glTextureStorage2D(lic_texture_, levels, GL_R8, sky.lic_size, sky.lic_size);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage2D(lic_texture_, 0, 0, 0, sky.lic_size, sky.lic_size, GL_RED, GL_UNSIGNED_BYTE,
                      texels.data());
  glGenerateTextureMipmap(lic_texture_);
  // Mipmapped: the plane is seen at grazing angles near the horizon.
  glTextureParameteri(lic_texture_, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTextureParameteri(lic_texture_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(lic_texture_, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTextureParameteri(lic_texture_, GL_TEXTURE_WRAP_T, GL_REPEAT);
  lic_key_ = key;
}

void SkyPass::ensureImageTexture(const SkySettings& sky) {
  if (image_texture_ && image_uploaded_ == sky.image.get()) return;
  if (image_texture_) glDeleteTextures(1, &image_texture_);
  const ImageRgba8& image = *sky.image;
  glCreateTextures(GL_TEXTURE_2D, 1, &image_texture_);
  glTextureStorage2D(image_texture_, 1, GL_RGBA8, image.width, image.height);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage2D(image_texture_, 0, 0, 0, image.width, image.height, GL_RGBA, GL_UNSIGNED_BYTE,
                      image.pixels.data());
  glTextureParameteri(image_texture_, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(image_texture_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(image_texture_, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(image_texture_, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  image_uploaded_ = sky.image.get();
  image_keep_ = sky.image;
}

bool SkyPass::draw(const Camera& camera, int w, int h, int frame_w, int frame_h,
                   const SkySettings& sky, RenderStyle style, const Light& light,
                   std::string* error) {
  const GLuint p = program(sky, style, error);
  if (!p) return false;
  if (!vao_) glCreateVertexArrays(1, &vao_);
  glUseProgram(p);
  auto loc = [&](const char* name) { return glGetUniformLocation(p, name); };
  const glm::mat4 inv =
      glm::inverse(camera.projection(float(frame_w) / float(frame_h)) * camera.view());
  glUniformMatrix4fv(loc("u_inv_view_proj"), 1, GL_FALSE, glm::value_ptr(inv));
  glUniform2f(loc("u_viewport"), float(w), float(h));
  glUniform2f(loc("u_sky_frame_size"), float(frame_w), float(frame_h));
  glUniform3fv(loc("u_sky_zenith"), 1, glm::value_ptr(sky.zenith));
  glUniform3fv(loc("u_sky_horizon"), 1, glm::value_ptr(sky.horizon));
  glUniform1f(loc("u_sky_glow"), sky.sun_glow);
  glUniform3fv(loc("u_sky_sun_dir"), 1, glm::value_ptr(light.direction));
  glUniform3fv(loc("u_sky_sun_colour"), 1, glm::value_ptr(light.colour));
  glUniform1f(loc("u_sky_lic_scale"), sky.lic_scale);
  glUniform1i(loc("u_sky_layer"), 5);
  glUniform1i(loc("u_sky_image"), 6);
  if (sky.kind == SkyKind::kLic) {
    ensureLicTexture(sky);
    glBindTextureUnit(5, lic_texture_);
  }
  if (sky.kind == SkyKind::kImage && sky.image) {
    ensureImageTexture(sky);
    glUniform2f(loc("u_sky_image_size"), float(sky.image->width), float(sky.image->height));
    glBindTextureUnit(6, image_texture_);
  }
  glDisable(GL_BLEND);
  glDisable(GL_STENCIL_TEST);
  glBindVertexArray(vao_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  return true;
}

}  // namespace cb
