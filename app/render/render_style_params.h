// Each render style's parameters (config/render.toml [style.NAME], render_config.cpp), with the
// values the styles were tuned with as defaults. The shaders receive them as uniforms; the CPU
// references of the styles (tests/unit/render/style_reference.cpp) read the same struct.
#pragma once

#include <glm/glm.hpp>

namespace cb {

// shade_physical.glsl (seed 004 and the additions listed there).
struct PhysicalStyleParams {
  float reflection = 0.55f;      // κ₁, seed 004 "Radiometric equations"
  float scattering = 0.45f;      // κ₂
  float forward_g = 0.6f;        // Henyey–Greenstein g of the forward lobe
  float back_g = -0.3f;          // and of the back lobe
  float forward_weight = 0.75f;  // blend of the two lobes
  int octaves = 3;               // multiple-scattering octaves, 1..3 (the light table holds 3)
  float ambient = 0.5f;          // κ_a: the sky's ambient light
  float exposure = 1.6f;         // 1 − e^(−exposure·c)
  float erosion = 0.6f;          // κ_e: fBm edge erosion
};

// shade_ink.glsl + ink_bleed.frag.glsl + style_compose.frag.glsl (seed 001).
struct InkStyleParams {
  float wash = 0.35f;               // darkest interior wash
  float line_width = 0.5f;          // silhouette threshold on N·V (§4.1.1): wider lines above
  float bleed_sigma = 1.41421356f;  // σ of the Gaussian ink bleeding, pixels (σ² = 2, §4.1.2)
  bool sky = false;                 // show the configured sky instead of bare xuan paper
};

// shade_cartoon.glsl (seed 003).
struct CartoonStyleParams {
  glm::vec3 band_thresholds{0.2f, 0.45f, 0.75f};  // d = N·L·(0.35 + 0.65·T) between the 4 tones
  float outline_width = 0.3f;  // outline where |N·V| < this (soft from half of it)
};

// shade_sketch.glsl + style_compose.frag.glsl (seed 003).
struct SketchStyleParams {
  float outline_width = 0.3f;  // as the cartoon's
  bool sky = false;            // show the configured sky instead of bare drawing paper
};

struct StyleParams {
  PhysicalStyleParams physical;
  InkStyleParams ink;
  CartoonStyleParams cartoon;
  SketchStyleParams sketch;
};

// Half width in pixels of the ink bleeding kernel for σ: the kernel spans ±⌈2.12σ⌉ (±3 at the
// seed's σ² = 2, kernel width 7), at most kMaxInkBleedRadius.
inline constexpr int kMaxInkBleedRadius = 8;
int inkBleedRadius(float sigma);

}  // namespace cb
