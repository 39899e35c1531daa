// Render styles: the run-time choice of how the ray caster turns density and light into colour.
// The thesis's shading curve (§4.5.2) is the default; the others come from the seed documents:
//
//   name        seed                          what it draws
//   "thesis"    Chen 2014 §4.5.2              composited volume, cosine shading curve
//   "physical"  Jiménez de Parga (seed 004)   composited volume, Beer–Lambert, Henyey–Greenstein,
//                                             in-scattering light grid, fBm edge erosion
//   "ink"       Cao 2016 (seed 001)           iso-surface, banded ink wash, blurred silhouette on
//                                             xuan paper (screen-space pass)
//   "cartoon"   Álvarez et al. (seed 003)     iso-surface, cel bands, outline, inner-surface lines
//   "sketch"    Álvarez et al. (seed 003)     iso-surface as pencil outline and hatching on paper
//
// The names are what config (render.toml `[style] name`), the command line (`--style NAME`) and
// the session journal use; they never change once shipped.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>

#include <glm/glm.hpp>

#include "app/render/render_style_params.h"

namespace cb {

enum class RenderStyle { kThesis, kPhysical, kInk, kCartoon, kSketch };

inline constexpr std::array<RenderStyle, 5> kAllRenderStyles = {
    RenderStyle::kThesis, RenderStyle::kPhysical, RenderStyle::kInk, RenderStyle::kCartoon,
    RenderStyle::kSketch};

// "thesis", "physical", "ink", "cartoon", "sketch".
const char* renderStyleName(RenderStyle style);
// The style with that name (exact, lower case), or nothing.
std::optional<RenderStyle> parseRenderStyle(std::string_view name);
// "thesis|physical|ink|cartoon|sketch" (for help texts and error messages).
std::string renderStyleNameList();

// The shading stage file (shaders/shade_<name>.glsl) linked in front of the ray caster.
const char* shadingStageFile(RenderStyle style);
// True when the style draws an iso-surface of the density (first hit along the ray) rather
// than compositing the whole volume.
bool drawsIsoSurface(RenderStyle style);
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

// True when the ray-cast image is finished by a screen-space pass (style_compose.frag.glsl):
// paper, ink bleeding, hatching.
bool hasScreenSpacePass(RenderStyle style);
// True when the shading stage reads screen-space derivatives (cartoon's inner line is held to
// two pixels by fwidth): an image cast at a fraction of the pixels does not reproduce it.
bool shadesWithScreenDerivatives(RenderStyle style);
// How far, in pixels of the ray-cast image, the style's screen-space pass reads around the pixel
// it writes (the Gaussian ink bleeding's half kernel; 0 for a style without such a pass).
//
// Partial re-rendering rule: to refresh a screen rectangle R of a style with reach r, ray cast R
// dilated by r on every side (clipped to the frame), then run the screen-space pass over R only.
// A pixel of R then reads only freshly cast pixels, so it equals a full-frame render.
int screenSpaceReach(RenderStyle style);
// The same for a style with these parameters (ink: the bleeding kernel of ink.bleed_sigma).
int screenSpaceReach(RenderStyle style, const StyleParams& params);

}  // namespace cb
