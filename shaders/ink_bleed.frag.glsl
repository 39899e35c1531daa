#version 450 core
// Ink bleeding, one axis of the separable Gaussian (seed 001 §3.3.5, §4.1.2): blurs the
// silhouette ink (g) of the ink style's ray-cast image along u_axis with kernel width 7 and
// G(x) ∝ e^(−x²/4) (the seed's G(x,y) = e^(−(x²+y²)/4)/4π, σ² = 2); r and a pass through.
// Reads 3 pixels either side: screenSpaceReach(kInk) in render_style.h.
layout(location = 0) out vec4 o_colour;
uniform sampler2D u_image;
uniform ivec2 u_axis;  // (1,0) or (0,1)

const float kWeights[4] = float[4](1.0, 0.7788008, 0.3678794, 0.1053992);  // e^(−x²/4)
const float kNorm = 1.0 / 3.5041589;  // 1 + 2·(sum of the others)

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  ivec2 last = textureSize(u_image, 0) - 1;
  vec4 centre = texelFetch(u_image, p, 0);
  float g = centre.g * kWeights[0];
  for (int i = 1; i < 4; ++i) {
    g += kWeights[i] * (texelFetch(u_image, clamp(p + i * u_axis, ivec2(0), last), 0).g +
                        texelFetch(u_image, clamp(p - i * u_axis, ivec2(0), last), 0).g);
  }
  o_colour = vec4(centre.r, g * kNorm, centre.b, centre.a);
}
