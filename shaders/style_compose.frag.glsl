#version 450 core
// Screen-space finish of the paper styles, from the ray-cast image u_image (one texel per
// ray; the output may be larger when the frame was cast at reduced scale). Both paper styles
// draw their outline in image space (seed 001 §2.5: silhouettes detected on the image plane):
// the coverage (a) blurred by a Gaussian of σ u_sigma (x in ink_bleed.frag.glsl into b, y here,
// blurredLines) crosses ½ on the silhouette, and 4·A·(1 − A) of the blurred coverage A is a line
// about 2σ wide that follows it without a break wherever the cloud meets the paper. The lines
// from N·V alone (shade_ink.glsl, shade_sketch.glsl) are under a pixel wide on a painted stroke a
// few tens of pixels thick (N·V < 0.15 within ~1 % of its radius of the edge) and broke into
// dashes, specks and bare stretches. With CB_BLEED 0 (moving) the image is not blurred and the
// line is that of the unblurred coverage.
//  CB_COMPOSE_INK (seed 001 §3.3.5, §4.1.3): ink = 1 − (1 − wash)(1 − silhouette), where the
//    silhouette is the N·V ink (g) blurred by the same Gaussian (the ink bleeding, σ² = 2) or the
//    outline, whichever is darker; grey = smoothstep(0.1, 0.92, 1 − ink) (the seed's edges); the
//    colour is the ink tone laid on xuan paper by grey.
//  CB_COMPOSE_SKETCH (seed 003, Fig. 2 and 6): pencil hatching, one more stroke direction per
//    tone level (r), wobbling and grainy, and the outline strokes (g, unblurred: the N·V outline
//    and the inner surface's lines) or the image-space outline in pencil, on drawing paper.
// Paper and strokes are functions of the output pixel, so they stay put while the cloud moves.
// CB_OVER_SKY ([style.ink] / [style.sketch] sky = true): the paper shows only inside the cloud
// (coverage a) and the output is premultiplied, blended over the sky drawn first (sky_pass.h):
//   C = (1 − grey)·ink + grey·a·paper + grey·(1 − a)·sky,  so  α = 1 − grey·(1 − a).
layout(location = 0) out vec4 o_colour;
uniform sampler2D u_image;
uniform sampler2D u_bleed;   // u_image with its g and its coverage (into b) blurred along x
uniform vec2 u_output_size;  // pixels
#if CB_BLEED
uniform float u_weight[CB_BLUR_RADIUS + 1];  // the blur's weights (ink_bleed.frag.glsl)
#endif

// Lays `stroke` (1 = full stroke colour) over `paper`; with CB_OVER_SKY the paper covers only the
// cloud and the rest stays transparent (premultiplied) for the sky beneath.
vec4 layOn(vec3 paper, vec3 stroke_colour, float paper_share, float coverage) {
#if CB_OVER_SKY
  return vec4((1.0 - paper_share) * stroke_colour + paper_share * coverage * paper,
              1.0 - paper_share * (1.0 - coverage));
#else
  return vec4(mix(stroke_colour, paper, paper_share), 1.0);
#endif
}

float hash(vec2 p) {
  uvec2 q = uvec2(ivec2(floor(p)) + 65536);
  uint h = q.x * 0x8da6b343u ^ q.y * 0xd8163841u;
  h ^= h >> 13;
  h *= 0x85ebca6bu;
  h ^= h >> 16;
  return float(h & 0xffffu) / 65535.0;
}

float valueNoise(vec2 p) {
  vec2 i = floor(p), f = fract(p);
  vec2 w = f * f * (3.0 - 2.0 * f);
  return mix(mix(hash(i), hash(i + vec2(1, 0)), w.x), mix(hash(i + vec2(0, 1)), hash(i + 1.0), w.x),
             w.y);
}

// (g, coverage) of the image blurred by the Gaussian: the second, y pass over u_bleed. With
// CB_FULL_SCALE (the image is the output's size) one texel fetch per tap; otherwise the taps are
// bilinear, the blurred image upscaled.
vec2 blurredLines(vec2 uv, vec4 image) {
#if CB_BLEED && CB_FULL_SCALE
  ivec2 p = ivec2(gl_FragCoord.xy);
  int last = textureSize(u_bleed, 0).y - 1;
  vec2 blurred = u_weight[0] * texelFetch(u_bleed, p, 0).gb;
  for (int i = 1; i <= CB_BLUR_RADIUS; ++i)
    blurred += u_weight[i] * (texelFetch(u_bleed, ivec2(p.x, min(p.y + i, last)), 0).gb +
                              texelFetch(u_bleed, ivec2(p.x, max(p.y - i, 0)), 0).gb);
  return blurred;
#elif CB_BLEED
  float texel = 1.0 / float(textureSize(u_bleed, 0).y);
  vec2 blurred = u_weight[0] * texture(u_bleed, uv).gb;
  for (int i = 1; i <= CB_BLUR_RADIUS; ++i)
    blurred += u_weight[i] * (texture(u_bleed, uv + vec2(0.0, float(i) * texel)).gb +
                              texture(u_bleed, uv - vec2(0.0, float(i) * texel)).gb);
  return blurred;
#else
  return image.ga;
#endif
}

// The image-space outline, 0 … 1: 1 where the blurred coverage crosses ½.
float coverageOutline(float blurred_coverage) {
  return 4.0 * blurred_coverage * (1.0 - blurred_coverage);
}

#if CB_COMPOSE_INK
const vec3 kInkTone = vec3(0.07, 0.07, 0.09);
// The image-space outline's ink at the silhouette: a grey line (seed 001 Fig. 4.3–4.4: soft,
// graded edges) that the N·V line darkens where the surface grazes the eye. At 0.75 the stroke
// gallery's outlines read as solid black rims (28 % of an s-curve's inked pixels dark, against
// 16 % with the dashed N·V line alone); at 0.6, 25 % and a grey line.
const float kOutlineInk = 0.6;

// Xuan paper: warm off-white with long fibres (noise stretched along x) and a fine grain.
vec3 xuanPaper(vec2 p) {
  float fibres = 0.6 * valueNoise(p * vec2(0.015, 0.12)) + 0.4 * valueNoise(p * vec2(0.05, 0.4));
  float grain = hash(p);
  return vec3(0.93, 0.90, 0.82) * (0.95 + 0.05 * fibres + 0.02 * grain);
}
#endif

#if CB_COMPOSE_SKETCH
const vec3 kGraphite = vec3(0.22, 0.22, 0.26);
// The image-space outline's pencil at the silhouette (before the grain's 0.75–1): as dark as the
// N·V outline drew where it held (seed 003 Fig. 6: a firm contour, lighter inner lines at 0.45).
const float kOutlinePencil = 0.9;

// 1 on a pencil line every `spacing` pixels along coordinate u, 0 between (soft edges).
float hatchLines(float u, float spacing) {
  float f = abs(fract(u / spacing) - 0.5) * 2.0;  // 1 on the line's centre
  return smoothstep(0.72, 0.92, f);
}
#endif

void main() {
  vec2 uv = gl_FragCoord.xy / u_output_size;
#if CB_FULL_SCALE
  vec4 image = texelFetch(u_image, ivec2(gl_FragCoord.xy), 0);
#else
  vec4 image = texture(u_image, uv);
#endif
  vec2 p = gl_FragCoord.xy;
#if CB_COMPOSE_INK
  vec2 blurred = blurredLines(uv, image);  // silhouette ink, coverage
  float outline = kOutlineInk * coverageOutline(blurred.y);
  float silhouette = max(blurred.x, outline);
  float ink = 1.0 - (1.0 - image.r) * (1.0 - silhouette);
  float grey = smoothstep(0.1, 0.92, 1.0 - ink);
  o_colour = layOn(xuanPaper(p), kInkTone, grey, image.a);
#elif CB_COMPOSE_SKETCH
  float wobble = (valueNoise(p * 0.03) - 0.5) * 5.0;
  float tone = image.r;
  float hatch = smoothstep(0.35, 0.45, tone) * hatchLines(p.x + p.y + wobble, 7.0);
  hatch = max(hatch, smoothstep(0.6, 0.7, tone) * hatchLines(p.x - p.y - wobble, 7.0));
  hatch = max(hatch, smoothstep(0.85, 0.95, tone) * hatchLines(p.y + 0.5 * wobble, 4.0));
  float grain = 0.65 + 0.35 * valueNoise(p * vec2(0.6, 0.08));
  float line = max(image.g, kOutlinePencil * coverageOutline(blurredLines(uv, image).y));
  float stroke = max(line * (0.75 + 0.25 * grain), 0.5 * hatch * grain);
  vec3 paper = vec3(0.97, 0.96, 0.93) * (0.97 + 0.03 * hash(p));
  o_colour = layOn(paper, kGraphite, 1.0 - stroke, image.a);
#else
  o_colour = image;
#endif
}
