#version 450 core
// Ink bleeding, one axis of the separable Gaussian (seed 001 §3.3.5, §4.1.2): blurs the
// silhouette ink (g) of the ink style's ray-cast image along u_axis with G(x) ∝ e^(−x²/(2σ²))
// over ±CB_BLUR_RADIUS pixels; the seed's G(x,y) = e^(−(x²+y²)/4)/4π is σ² = 2 with kernel width 7
// (radius 3), the default ([style.ink] bleed_sigma). The coverage (a) is blurred the same way into
// b, for the outline the compose pass draws where the blurred coverage crosses ½ (image-space
// silhouette detection, seed 001 §2.5); the sketch style runs this pass too, for that outline
// alone (σ = 0.85, screenBlurSigma). r and a pass through. Reads inkBleedRadius(σ) pixels either
// side: screenSpaceReach(style, params) in render_style.h. The radius is compiled in
// (CB_BLUR_RADIUS) and the normalised weights are uniforms (screen_blur.h), so the loop unrolls
// into one texel fetch per tap and no exp.
layout(location = 0) out vec4 o_colour;
uniform sampler2D u_image;
uniform ivec2 u_axis;                        // (1,0) or (0,1)
uniform float u_weight[CB_BLUR_RADIUS + 1];  // weights of offsets 0, ±1 … ±CB_BLUR_RADIUS

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  ivec2 last = textureSize(u_image, 0) - 1;
  vec4 centre = texelFetch(u_image, p, 0);
  vec2 ga = u_weight[0] * centre.ga;
  for (int i = 1; i <= CB_BLUR_RADIUS; ++i)
    ga += u_weight[i] * (texelFetch(u_image, clamp(p + i * u_axis, ivec2(0), last), 0).ga +
                         texelFetch(u_image, clamp(p - i * u_axis, ivec2(0), last), 0).ga);
  o_colour = vec4(centre.r, ga, centre.a);
}
