// Render styles: the run-time choice of how the ray caster turns density and light into colour.
// The thesis's shading curve (§4.5.2) is the default; the others come from the seed documents
// (ink: Cao 2016, seed 001; cartoon and sketch: Álvarez et al., seed 003; physical: Jiménez de
// Parga, seed 004). Each style is one row of kRenderStyleRows below.
#pragma once

#include <array>
#include <cstddef>
#include <iterator>
#include <optional>
#include <string>
#include <string_view>

#include <glm/glm.hpp>

#include "app/render/render_style_params.h"

namespace cb {

enum class RenderStyle { kThesis, kPhysical, kInk, kCartoon, kSketch };

// The screen-space pass that finishes a style's ray-cast image (style_compose.frag.glsl).
enum class ScreenPass {
  kNone,         // the ray cast writes the frame
  kInkWash,      // Gaussian ink bleeding (ink_bleed.frag.glsl), smoothstep, xuan paper (seed 001)
  kSketchPaper,  // pencil lines and hatching on drawing paper (seed 003)
  // Both blur the coverage by a Gaussian (screenBlurSigma) for the image-space outline.
};

// Everything the renderer, the sky and the temporal reprojection ask of a style: one row each,
// in the enum's order. Adding a style: its enum value, its row, its shaders/shade_NAME.glsl (and,
// if it has parameters, their struct in render_style_params.h and their fields in
// render_config.cpp's field list).
struct RenderStyleRow {
  RenderStyle style;
  // The name config (render.toml `[style] name`), the command line (`--style NAME`) and the
  // session journal use; never changes once shipped.
  const char* name;
  const char* stage;  // the shading stage (shaders/) linked in front of the ray caster
  // Draws an iso-surface of the density (first hit along the ray) rather than compositing the
  // whole volume: compiled with CB_SURFACE, linked after surface_sample.glsl.
  bool iso_surface;
  ScreenPass screen_pass;
  // The shading stage reads screen-space derivatives (cartoon's inner line is held to two pixels
  // by fwidth): an image cast at a fraction of the pixels does not reproduce it.
  bool screen_derivatives;
  // The temporal reprojection may make its full frame from a 1/f cast: only for a style whose
  // pixels are independent of their neighbours (no screen pass, no screen derivatives).
  bool reprojects;
  bool posterised_sky;  // the sky drawn in bands (CB_SKY_POSTERISE, sky_function.cpp)
  // Whether the configured sky shows behind the cloud; null: whenever one is configured.
  bool (*shows_sky)(const StyleParams&);
  // The outline width uniform (u_outline_width) of a stage that draws outlines; null: none.
  float (*outline_width)(const StyleParams&);
  // Samples the multiple-scattering light table and the fBm detail noise (shade_physical.glsl).
  bool light_table;
};

inline constexpr RenderStyleRow kRenderStyleRows[] = {
    // Chen 2014 §4.5.2: composited volume, cosine shading curve.
    {RenderStyle::kThesis, "thesis", "shade_thesis.glsl", false, ScreenPass::kNone, false, true,
     false, nullptr, nullptr, false},
    // Jiménez de Parga (seed 004): Beer–Lambert, Henyey–Greenstein, in-scattering light grid,
    // fBm edge erosion.
    {RenderStyle::kPhysical, "physical", "shade_physical.glsl", false, ScreenPass::kNone, false,
     true, false, nullptr, nullptr, true},
    // Cao 2016 (seed 001): banded ink wash, blurred silhouette on xuan paper.
    {RenderStyle::kInk, "ink", "shade_ink.glsl", true, ScreenPass::kInkWash, false, false, false,
     [](const StyleParams& p) { return p.ink.sky; }, nullptr, false},
    // Álvarez et al. (seed 003): cel bands, outline, inner-surface lines; a posterised sky.
    {RenderStyle::kCartoon, "cartoon", "shade_cartoon.glsl", true, ScreenPass::kNone, true, false,
     true, nullptr, [](const StyleParams& p) { return p.cartoon.outline_width; }, false},
    // Álvarez et al. (seed 003): pencil outline and hatching on paper.
    {RenderStyle::kSketch, "sketch", "shade_sketch.glsl", true, ScreenPass::kSketchPaper, false,
     false, false, [](const StyleParams& p) { return p.sketch.sky; },
     [](const StyleParams& p) { return p.sketch.outline_width; }, false},
};
inline constexpr size_t kRenderStyleCount = std::size(kRenderStyleRows);

constexpr bool renderStyleRowsHoldTheirRules() {
  for (size_t i = 0; i < kRenderStyleCount; ++i) {
    const RenderStyleRow& r = kRenderStyleRows[i];
    if (size_t(r.style) != i) return false;  // rows in the enum's order
    if (r.reprojects && (r.screen_pass != ScreenPass::kNone || r.screen_derivatives)) return false;
  }
  return true;
}
static_assert(renderStyleRowsHoldTheirRules(),
              "kRenderStyleRows: one row per enum value in order; no reprojection with a screen "
              "pass or screen derivatives");

constexpr const RenderStyleRow& renderStyleRow(RenderStyle style) {
  return kRenderStyleRows[size_t(style)];
}

inline constexpr std::array<RenderStyle, kRenderStyleCount> kAllRenderStyles = [] {
  std::array<RenderStyle, kRenderStyleCount> all{};
  for (size_t i = 0; i < kRenderStyleCount; ++i) all[i] = kRenderStyleRows[i].style;
  return all;
}();

// "thesis", "physical", "ink", "cartoon", "sketch".
const char* renderStyleName(RenderStyle style);
// The style with that name (exact, lower case), or nothing.
std::optional<RenderStyle> parseRenderStyle(std::string_view name);
// "thesis|physical|ink|cartoon|sketch" (for help texts and error messages).
std::string renderStyleNameList();

// The row's stage, iso_surface, screen pass and screen derivatives, for callers that ask one.
const char* shadingStageFile(RenderStyle style);
bool drawsIsoSurface(RenderStyle style);
bool hasScreenSpacePass(RenderStyle style);
bool shadesWithScreenDerivatives(RenderStyle style);
// Where an iso-surface style reads the density around a hit (raycast.frag.glsl, CB_SURFACE), in
// voxels per axis of a grid with this voxel size (world units), held at a world size on any
// grid (the thesis's box, 256³ voxels over [-1,1]³, and the painter's 1024-voxel sky share the
// voxel 2/256): the normal's central differences 1 voxel apart and 6 % of the box behind the
// hit (seed 003 §5). A painted cloud's surface is eroded by noise at the voxel scale (mapping
// spheres.noise_erosion): a stencil 4 voxels wide sampled across those bumps and turned the
// normal edge-on inside the cloud, which the styles draw as silhouette ink (painted strokes at
// 1920×1080: 3.5 % of ink's pixels in solid dark patches, cartoon 1.4 %, sketch 2.0 %; at 1 voxel
// 0.12, 0.02, 0.01 %; tests/unit/session/painted_styles_test.cpp). A fraction of the sky's
// width (16 voxels) was worse still: it straddled a stroke's whole thickness.
struct IsoSurfaceReach {
  float gradient_voxels = 1.0f;     // central differences this far apart (at least 1 voxel)
  float inner_depth_voxels = 0.0f;  // searched behind the hit for the inner surface
};
IsoSurfaceReach isoSurfaceReach(glm::vec3 voxel_size);

// σ in pixels of the Gaussian a style's screen-space pass blurs its image by (the coverage for the
// image-space outline; ink: also the bleeding of its silhouette ink): ink.bleed_sigma for ink,
// kSketchOutlineSigma for sketch; 0 for a style without such a pass.
float screenBlurSigma(RenderStyle style, const StyleParams& params);
// The sketch's outline blur: σ = 0.85 pixel draws 4A(1 − A) as a pencil line about 2 pixels wide
// (the ink's σ² = 2 brush line is about 3) over 5 taps (radius 2). At σ = 1 (7 taps) the line's
// overlap with the N·V line filled 1.0–1.2 % of two gallery strokes in solid patches.
inline constexpr float kSketchOutlineSigma = 0.85f;

// How far, in pixels of the ray-cast image, the style's screen-space pass reads around the pixel
// it writes (the Gaussian blur's half kernel; 0 for a style without such a pass).
//
// Partial re-rendering rule: to refresh a screen rectangle R of a style with reach r, ray cast R
// dilated by r on every side (clipped to the frame), then run the screen-space pass over R only.
// A pixel of R then reads only freshly cast pixels, so it equals a full-frame render.
int screenSpaceReach(RenderStyle style);
// The same for a style with these parameters (the kernel of screenBlurSigma).
int screenSpaceReach(RenderStyle style, const StyleParams& params);

}  // namespace cb
