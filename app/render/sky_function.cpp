#include "app/render/sky_function.h"

#include <algorithm>
#include <cmath>

namespace cb {
namespace {

float smoothStep(float e0, float e1, float x) {
  const float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

// GL_LINEAR with GL_REPEAT on a size×size R8 texture at texture coordinate uv.
float licBilinear(const std::vector<uint8_t>& texels, int size, glm::vec2 uv) {
  const glm::vec2 u = uv * float(size) - 0.5f;
  const glm::vec2 i0 = glm::floor(u);
  const glm::vec2 f = u - i0;
  auto at = [&](int x, int y) {
    x = ((x % size) + size) % size;
    y = ((y % size) + size) % size;
    return float(texels[size_t(y) * size_t(size) + size_t(x)]) / 255.0f;
  };
  const int x = int(i0.x), y = int(i0.y);
  return glm::mix(glm::mix(at(x, y), at(x + 1, y), f.x),
                  glm::mix(at(x, y + 1), at(x + 1, y + 1), f.x), f.y);
}

// GL_LINEAR with GL_CLAMP_TO_EDGE on an RGBA8 image at texel coordinates t (centres at i + ½).
glm::vec3 imageBilinear(const ImageRgba8& image, glm::vec2 t) {
  const glm::vec2 u = t - 0.5f;
  const glm::vec2 i0 = glm::floor(u);
  const glm::vec2 f = u - i0;
  auto at = [&](int x, int y) {
    x = std::clamp(x, 0, image.width - 1);
    y = std::clamp(y, 0, image.height - 1);
    const uint8_t* p = image.at(x, y);
    return glm::vec3(p[0], p[1], p[2]) / 255.0f;
  };
  const int x = int(i0.x), y = int(i0.y);
  return glm::mix(glm::mix(at(x, y), at(x + 1, y), f.x),
                  glm::mix(at(x, y + 1), at(x + 1, y + 1), f.x), f.y);
}

// The cartoon's posterising of a parameter into `levels` steps (sky.glsl's posterise).
float posterise(const SkyScene& s, float v, float levels) {
  return renderStyleRow(s.style).posterised_sky ? std::floor(v * levels + 0.5f) / levels : v;
}

float gradientT(glm::vec3 dir) {
  return std::pow(1.0f - std::max(dir.y, 0.0f), 3.0f);
}
float glowAmount(const SkyScene& s, glm::vec3 dir) {
  return std::pow(std::max(glm::dot(dir, s.sun_dir), 0.0f), 24.0f);
}
float layerOpacity(const SkyScene& s, glm::vec3 dir) {
  const glm::vec2 uv = glm::vec2(dir.x, dir.z) / std::max(dir.y, 1e-3f) * s.settings.lic_scale;
  return licBilinear(*s.lic, s.settings.lic_size, uv) * smoothStep(0.03f, 0.3f, dir.y);
}

glm::vec3 gradient(const SkyScene& s, glm::vec3 dir) {
  const float t = posterise(s, gradientT(dir), 5.0f);
  const float glow = posterise(s, glowAmount(s, dir), 3.0f);
  return glm::mix(s.settings.zenith, s.settings.horizon, t) +
         s.settings.sun_glow * glow * s.sun_colour;
}

}  // namespace

glm::vec2 skyImageTexel(int image_width, int image_height, int frame_width, int frame_height,
                        glm::vec2 pixel) {
  const float scale =
      std::max(float(frame_width) / float(image_width), float(frame_height) / float(image_height));
  const glm::vec2 from_centre = pixel - 0.5f * glm::vec2(frame_width, frame_height);
  // Image rows run top-down, pixel y bottom-up.
  return 0.5f * glm::vec2(image_width, image_height) +
         glm::vec2(from_centre.x, -from_centre.y) / scale;
}

glm::vec3 skyColour(const SkyScene& s, glm::vec3 dir, glm::vec2 pixel) {
  glm::vec3 c(0.0f);
  switch (s.settings.kind) {
    case SkyKind::kNone:
      return c;
    case SkyKind::kColour:
      c = gradient(s, dir);
      break;
    case SkyKind::kLic: {
      c = gradient(s, dir);
      if (s.lic && dir.y > 0.0f) {
        const float o = posterise(s, layerOpacity(s, dir), 3.0f);
        c = glm::mix(c, 0.92f * s.sun_colour + 0.08f * s.settings.horizon, 0.85f * o);
      }
      break;
    }
    case SkyKind::kImage:
      if (s.settings.image)
        c = imageBilinear(*s.settings.image,
                          skyImageTexel(s.settings.image->width, s.settings.image->height,
                                        s.frame_width, s.frame_height, pixel));
      break;
  }
  if (renderStyleRow(s.style).posterised_sky && s.settings.kind == SkyKind::kImage) {
    // A picture: its luminance in 5 bands, hues kept.
    const float luma = glm::dot(c, glm::vec3(0.2126f, 0.7152f, 0.0722f));
    c *= (std::floor(luma * 5.0f + 0.5f) / 5.0f) / std::max(luma, 1e-3f);
  }
  return glm::clamp(c, 0.0f, 1.0f);
}

bool skyNearPosteriseStep(const SkyScene& s, glm::vec3 dir, float margin) {
  // (An image's luminance bands depend on the pixel, not dir: not covered here.)
  if (!renderStyleRow(s.style).posterised_sky) return false;
  auto near = [&](float v, float levels) {
    const float x = v * levels + 0.5f;
    return std::abs(x - std::round(x)) < margin * levels;
  };
  bool result = near(gradientT(dir), 5.0f) || near(glowAmount(s, dir), 3.0f);
  if (s.settings.kind == SkyKind::kLic && s.lic && dir.y > 0.0f)
    result = result || near(layerOpacity(s, dir), 3.0f);
  return result;
}

glm::vec3 skyAmbientColour(const SkySettings& settings) {
  return glm::mix(settings.zenith, settings.horizon, 0.5f);
}

}  // namespace cb
