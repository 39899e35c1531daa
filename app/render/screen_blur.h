#pragma once
// The screen-space passes' separable Gaussian (ink_bleed.frag.glsl along x, style_compose.frag.glsl
// along y), G(x) ∝ e^(−x²/(2σ²)) over ±R texels, R = inkBleedRadius(σ): the radius is compiled
// into the passes (`CB_BLUR_RADIUS`, so the tap loop unrolls) and the weights are uniforms
// computed once here instead of an exp per tap and pixel. Each tap is one texelFetch: on
// llvmpipe a bilinear fetch costs more than the two texel fetches it would replace (two-texel
// bilinear taps made the sketch's still frame 1.6× → 1.9–2.1× the thesis style's).
#include <array>
#include <string>

#include "app/render/render_style_params.h"

namespace cb {

// weights[i] for offsets ±i (i = 0 … radius), normalised over the whole kernel
// (weights[0] + 2·Σ weights[i ≥ 1] = 1); entries past the radius are 0.
using ScreenBlurWeights = std::array<float, kMaxInkBleedRadius + 1>;
ScreenBlurWeights screenBlurWeights(float sigma, int radius);

// "#define CB_BLUR_RADIUS R\n", the passes' compile-time radius.
std::string screenBlurDefine(int radius);

}  // namespace cb
