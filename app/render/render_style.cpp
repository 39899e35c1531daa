#include "app/render/render_style.h"

#include <algorithm>
#include <cmath>

namespace cb {

const char* renderStyleName(RenderStyle style) {
  return renderStyleRow(style).name;
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
  return renderStyleRow(style).stage;
}

bool drawsIsoSurface(RenderStyle style) {
  return renderStyleRow(style).iso_surface;
}

bool hasScreenSpacePass(RenderStyle style) {
  return renderStyleRow(style).screen_pass != ScreenPass::kNone;
}

bool shadesWithScreenDerivatives(RenderStyle style) {
  return renderStyleRow(style).screen_derivatives;
}

int screenSpaceReach(RenderStyle style) {
  // Ink: Gaussian kernel width 7 (seed 001 §4.1.2), so 3 pixels each side; sketch's σ = 0.85:
  // 2 pixels (paper and hatching are functions of the pixel's position).
  return screenSpaceReach(style, StyleParams{});
}

float screenBlurSigma(RenderStyle style, const StyleParams& params) {
  switch (renderStyleRow(style).screen_pass) {
    case ScreenPass::kInkWash:
      return params.ink.bleed_sigma;
    case ScreenPass::kSketchPaper:
      return kSketchOutlineSigma;
    case ScreenPass::kNone:
      break;
  }
  return 0.0f;
}

int screenSpaceReach(RenderStyle style, const StyleParams& params) {
  return hasScreenSpacePass(style) ? inkBleedRadius(screenBlurSigma(style, params)) : 0;
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
