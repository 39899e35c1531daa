#include "app/render/render_style.h"

#include <algorithm>
#include <cmath>

namespace cb {

const char* renderStyleName(RenderStyle style) {
  switch (style) {
    case RenderStyle::kThesis:
      return "thesis";
    case RenderStyle::kPhysical:
      return "physical";
    case RenderStyle::kInk:
      return "ink";
    case RenderStyle::kCartoon:
      return "cartoon";
    case RenderStyle::kSketch:
      return "sketch";
  }
  return "thesis";
}

std::optional<RenderStyle> parseRenderStyle(std::string_view name) {
  for (RenderStyle s : kAllRenderStyles)
    if (name == renderStyleName(s)) return s;
  return std::nullopt;
}

std::string renderStyleNameList() {
  std::string list;
  for (RenderStyle s : kAllRenderStyles)
    list += (list.empty() ? "" : "|") + std::string(renderStyleName(s));
  return list;
}

const char* shadingStageFile(RenderStyle style) {
  switch (style) {
    case RenderStyle::kThesis:
      return "shade_thesis.glsl";
    case RenderStyle::kPhysical:
      return "shade_physical.glsl";
    case RenderStyle::kInk:
      return "shade_ink.glsl";
    case RenderStyle::kCartoon:
      return "shade_cartoon.glsl";
    case RenderStyle::kSketch:
      return "shade_sketch.glsl";
  }
  return "shade_thesis.glsl";
}

bool drawsIsoSurface(RenderStyle style) {
  return style == RenderStyle::kInk || style == RenderStyle::kCartoon ||
         style == RenderStyle::kSketch;
}

bool hasScreenSpacePass(RenderStyle style) {
  return style == RenderStyle::kInk || style == RenderStyle::kSketch;
}

bool shadesWithScreenDerivatives(RenderStyle style) {
  return style == RenderStyle::kCartoon;
}

int screenSpaceReach(RenderStyle style) {
  // Ink: Gaussian kernel width 7 (seed 001 §4.1.2), so 3 pixels each side. Sketch's pass reads
  // only its own pixel (paper and hatching are functions of the pixel's position).
  return screenSpaceReach(style, StyleParams{});
}

int screenSpaceReach(RenderStyle style, const StyleParams& params) {
  return style == RenderStyle::kInk ? inkBleedRadius(params.ink.bleed_sigma) : 0;
}

int inkBleedRadius(float sigma) {
  // ±2.12σ holds 97% of the Gaussian's weight; the seed's σ = √2 gives 2.9995 → 3.
  const int r = int(std::ceil(2.1213f * sigma - 1e-3f));
  return std::clamp(r, 1, kMaxInkBleedRadius);
}

IsoSurfaceReach isoSurfaceReach(glm::vec3 voxel_size) {
  // World distances of the thesis box's 1 voxel and 0.06 × 256 voxels (voxel 2/256).
  constexpr float kGradientWorld = 1.0f * 2.0f / 256.0f;
  constexpr float kInnerDepthWorld = 0.06f * 2.0f;
  const float voxel = std::max({voxel_size.x, voxel_size.y, voxel_size.z});
  return {std::max(1.0f, kGradientWorld / voxel), kInnerDepthWorld / voxel};
}

}  // namespace cb
