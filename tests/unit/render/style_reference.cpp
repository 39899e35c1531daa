#include "tests/unit/render/style_reference.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "app/render/brick_pool.h"
#include "app/render/sky_function.h"
#include "app/render/sky_pass.h"

namespace cb {
namespace {

constexpr float kPi = 3.14159265358979f;

float smoothStep(float e0, float e1, float x) {
  float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

float quantise8(float v) {
  return std::round(std::clamp(v, 0.0f, 1.0f) * 255.0f) / 255.0f;
}

// Trilinear filtering at texture coordinate tc as the GPU does it: the 8 voxels around it, each
// weighted (`weighted(voxel, weight)` gives the voxel's weighted value), summed in a fixed order.
template <class Weighted>
float trilinear(const ReferenceScene& s, glm::vec3 tc, Weighted weighted) {
  glm::vec3 u = tc * glm::vec3(s.dims) - 0.5f;
  glm::vec3 i0 = glm::floor(u);
  glm::vec3 f = u - i0;
  float sum = 0.0f;
  for (int k = 0; k < 8; ++k) {
    glm::ivec3 o(k & 1, (k >> 1) & 1, (k >> 2) & 1);
    glm::ivec3 v = glm::clamp(glm::ivec3(i0) + o, glm::ivec3(0), s.dims - 1);
    float w = (o.x ? f.x : 1 - f.x) * (o.y ? f.y : 1 - f.y) * (o.z ? f.z : 1 - f.z);
    sum += weighted(v, w);
  }
  return sum;
}

// Trilinear fetch of channel c (0 density, 1 transmittance) at texture coordinate tc.
float fetch(const ReferenceScene& s, glm::vec3 tc, int c) {
  return trilinear(s, tc, [&](glm::ivec3 v, float w) {
    size_t idx = (size_t(v.z) * s.dims.y + v.y) * s.dims.x + v.x;
    return w * float(s.voxels[idx * 2 + c]) / 255.0f;
  });
}

// The smoothed density of voxel v (app/render/brick_pool.h, packSmoothSlot): the mean of the 8
// density bytes (±1, ±1, ±1) from it, indices clamped to the grid, as a 16-bit unorm.
float smoothedVoxel(const ReferenceScene& s, glm::ivec3 v) {
  int sum = 0;
  for (int k = 0; k < 8; ++k) {
    const glm::ivec3 o((k & 1) ? 1 : -1, (k & 2) ? 1 : -1, (k & 4) ? 1 : -1);
    const glm::ivec3 n = glm::clamp(v + o, glm::ivec3(0), s.dims - 1);
    sum += s.voxels[((size_t(n.z) * s.dims.y + n.y) * s.dims.x + n.x) * 2];
  }
  return float(smoothUnorm16(sum)) / 65535.0f;
}

// Trilinear fetch of the smoothed density at texture coordinate tc.
float fetchSmoothed(const ReferenceScene& s, glm::vec3 tc) {
  return trilinear(s, tc, [&](glm::ivec3 v, float w) { return w * smoothedVoxel(s, v); });
}

// Nearest, repeating fetch of the fBm cube.
float fetchNoise(const DetailNoise& n, glm::vec3 tc) {
  glm::ivec3 i = glm::ivec3(glm::floor(tc * float(n.size)));
  i = ((i % n.size) + n.size) % n.size;
  return float(n.texels[(size_t(i.z) * n.size + i.y) * n.size + i.x]) / 255.0f;
}

struct Ray {
  glm::vec3 dir_world;    // unnormalised, near to far plane
  glm::vec3 base, delta;  // texture coordinate of sample k: base + k·delta
  int n = 0;              // samples
  bool inside = false;
};

// The ray through pixel centre (x + ½, y + ½) with y counted from the bottom (OpenGL).
Ray makeRay(const ReferenceScene& s, int x, int y_from_bottom) {
  glm::mat4 inv =
      glm::inverse(s.camera.projection(float(s.width) / float(s.height)) * s.camera.view());
  glm::vec2 ndc = (glm::vec2(x, y_from_bottom) + 0.5f) / glm::vec2(s.width, s.height) * 2.0f - 1.0f;
  glm::vec4 nh = inv * glm::vec4(ndc, -1, 1), fh = inv * glm::vec4(ndc, 1, 1);
  glm::vec3 ow = glm::vec3(nh) / nh.w;
  Ray r;
  r.dir_world = glm::vec3(fh) / fh.w - ow;
  glm::vec3 voxel = (s.world_max - s.world_min) / glm::vec3(s.dims);
  glm::vec3 o = (ow - s.world_min) / voxel;
  glm::vec3 d = glm::normalize(r.dir_world / voxel);
  float t_enter = 0.0f, t_exit = 1e30f;
  for (int a = 0; a < 3; ++a) {
    float inv_d = 1.0f / (std::abs(d[a]) < 1e-12f ? 1e-12f : d[a]);
    float ta = -o[a] * inv_d, tb = (float(s.dims[a]) - o[a]) * inv_d;
    t_enter = std::max(t_enter, std::min(ta, tb));
    t_exit = std::min(t_exit, std::max(ta, tb));
  }
  const float step = s.options.step_voxels;
  r.inside = t_exit > t_enter;
  r.n = r.inside ? int(std::ceil((t_exit - t_enter) / step)) : 0;
  r.base = (o + (t_enter + 0.5f * step) * d) / glm::vec3(s.dims);
  r.delta = d * step / glm::vec3(s.dims);
  return r;
}

// ---- Composited styles -------------------------------------------------------------------

// Thesis §4.5.2, Fig. 4.19: S = 0.55 + cos(0.4 − (1 − T)·π)/2.2.
glm::vec3 thesisEmission(const ReferenceScene& s, float t) {
  return (0.55f + std::cos(0.4f - (1.0f - t) * kPi) / 2.2f) * s.light.colour;
}

float hg4Pi(float cos_theta, float g) {
  return (1 - g * g) / std::pow(1 + g * g - 2 * g * cos_theta, 1.5f);
}

// Seed 004: L = T·(1 + κ_s·τ) per octave of optical depth bⁱτ; emission
// sun·(κ₁L₀ + κ₂·Σ aⁱ·Pᵢ·Lᵢ) + sky·κ_a·e^(−τ/8); two-lobe HG with g scaled by cⁱ.
glm::vec3 physicalEmission(const ReferenceScene& s, float t, float cos_theta) {
  const PhysicalStyleParams& p = s.options.style_params.physical;
  const float tau = -std::log(std::max(t, 1.0f / 512.0f));
  auto grid = [](float x) { return std::exp(-x) * (1 + 0.6f * x); };
  float scattered = 0.0f, weight = 1.0f, g = 1.0f, depth = 1.0f;
  for (int i = 0; i < p.octaves; ++i) {
    float phase = (1 - p.forward_weight) * hg4Pi(cos_theta, p.back_g * g) +
                  p.forward_weight * hg4Pi(cos_theta, p.forward_g * g);
    scattered += weight * phase * grid(depth * tau);
    weight *= 0.5f;
    g *= 0.5f;
    depth *= 0.5f;
  }
  const glm::vec3 ambient_colour =
      SkyPass::shows(s.options.sky, s.options.style, s.options.style_params)
          ? skyAmbientColour(s.options.sky)
          : glm::vec3(s.options.background);
  glm::vec3 sky = ambient_colour * p.ambient * std::exp(-tau / 8.0f);
  return s.light.colour * (p.reflection * grid(tau) + p.scattering * scattered) + sky;
}

// What shows behind the cloud at pixel (x, y from the bottom): the flat background or the sky.
glm::vec4 behind(const ReferenceScene& s, const Ray& r, int x, int y_from_bottom) {
  if (!SkyPass::shows(s.options.sky, s.options.style, s.options.style_params))
    return s.options.background;
  SkyScene sky;
  sky.settings = s.options.sky;
  sky.style = s.options.style;
  sky.sun_dir = s.light.direction;
  sky.sun_colour = s.light.colour;
  sky.lic = s.sky_lic;
  sky.frame_width = s.width;
  sky.frame_height = s.height;
  return glm::vec4(skyColour(sky, glm::normalize(r.dir_world), glm::vec2(x, y_from_bottom) + 0.5f),
                   1.0f);
}

glm::vec4 compositedPixel(const ReferenceScene& s, const Ray& r, glm::vec4 background) {
  const bool physical = s.options.style == RenderStyle::kPhysical;
  const float cos_theta = glm::dot(glm::normalize(r.dir_world), s.light.direction);
  const glm::vec3 repeat = glm::vec3(s.dims) / 32.0f;  // kDetailNoisePeriodVoxels
  glm::vec3 colour(0.0f);
  float transmittance = 1.0f;
  const float sigma_step = s.options.extinction_per_voxel * s.options.step_voxels;
  for (int k = 0; k < r.n && transmittance >= s.options.termination_transmittance; ++k) {
    glm::vec3 tc = r.base + float(k) * r.delta;
    float d = fetch(s, tc, 0), t = fetch(s, tc, 1);
    if (physical)
      d = std::max(
          d - s.options.style_params.physical.erosion * fetchNoise(s.noise, tc * repeat) * (1 - d),
          0.0f);
    float alpha = 1.0f - std::exp(-sigma_step * d);  // Beer–Lambert over the step
    glm::vec3 e = physical ? physicalEmission(s, t, cos_theta) : thesisEmission(s, t);
    colour += transmittance * alpha * e;
    transmittance *= 1.0f - alpha;
  }
  if (physical) {
    float opacity = 1.0f - transmittance;
    glm::vec3 emitted = colour / std::max(opacity, 1e-4f);
    colour =
        (glm::vec3(1.0f) - glm::exp(-s.options.style_params.physical.exposure * emitted)) * opacity;
  }
  const glm::vec4 bg = background;
  return glm::vec4(colour + transmittance * glm::vec3(bg),
                   1 - transmittance + transmittance * bg.a);
}

// ---- Iso-surface styles -------------------------------------------------------------------

struct Surface {
  bool hit = false, ambiguous = false;
  glm::vec3 normal{0.0f}, view{0.0f};
  float light_t = 1.0f, max_density = 0.0f, inner_max = 0.0f;
};

Surface findSurface(const ReferenceScene& s, const Ray& r) {
  Surface out;
  out.view = -glm::normalize(r.dir_world);
  float previous = 0.0f, hit_density = 0.0f;
  int hit_k = 0;
  for (int k = 0; k < r.n; ++k) {
    float d = fetch(s, r.base + float(k) * r.delta, 0);
    if (std::abs(d - kReferenceIso) < 2e-3f) out.ambiguous = true;
    if (d >= kReferenceIso) {
      out.hit = true;
      hit_density = d;
      hit_k = k;
      break;
    }
    previous = d;
    out.max_density = std::max(out.max_density, d);
  }
  if (!out.hit) return out;
  float f =
      std::clamp((kReferenceIso - previous) / std::max(hit_density - previous, 1e-6f), 0.f, 1.f);
  glm::vec3 p = r.base + (float(hit_k) - 1.0f + f) * r.delta;
  const float spacing =
      std::max(1.0f, float(std::max({s.dims.x, s.dims.y, s.dims.z})) / 64.0f);  // voxels
  glm::vec3 h = spacing / glm::vec3(s.dims);
  glm::vec3 grad;
  for (int a = 0; a < 3; ++a) {
    glm::vec3 e(0.0f);
    e[a] = h[a];
    grad[a] = fetch(s, p + e, 0) - fetch(s, p - e, 0);
  }
  glm::vec3 g = grad / ((s.world_max - s.world_min) / glm::vec3(s.dims));
  out.normal = glm::dot(g, g) > 1e-12f ? -glm::normalize(g) : out.view;
  out.light_t = fetch(s, p, 1);
  const int depth = int(kReferenceInnerDepthFraction *
                        float(std::max({s.dims.x, s.dims.y, s.dims.z})) / s.options.step_voxels);
  // The inner surface reads the density smoothed over about 3 voxels (the brick pool's
  // companion, raycast.frag.glsl).
  out.inner_max = 0.0f;
  for (int j = hit_k; j < std::max(hit_k + 1, std::min(r.n, hit_k + 1 + depth)); ++j)
    out.inner_max = std::max(out.inner_max, fetchSmoothed(s, r.base + float(j) * r.delta));
  return out;
}

// The outline and inner-line ramps turn a normal (a difference of two filtered densities) or a
// density into a colour with a steep slope; llvmpipe filters 8-bit texels with less precision
// than this float reference, so in those ramps a few /255 of density become several /255 of
// colour. True where the pixel sits on such a ramp.
bool outlineSensitive(const Surface& f) {
  const float edge = std::abs(glm::dot(f.normal, f.view));
  return (edge > 0.05f && edge < 0.6f) || std::abs(f.inner_max - kReferenceInnerIso) < 0.08f;
}

bool near(float v, std::initializer_list<float> thresholds, float eps) {
  for (float t : thresholds)
    if (std::abs(v - t) < eps) return true;
  return false;
}

// Seed 003: four cel tones by d = N·L·(0.35 + 0.65·T), outline where |N·V| < 0.3, inner-surface
// silhouette.
glm::vec4 cartoonPixel(const ReferenceScene& s, const Surface& f, glm::vec3 bg, bool* ambiguous,
                       bool* sensitive) {
  const glm::vec3 outline_colour(0.10f, 0.12f, 0.22f);
  const CartoonStyleParams& p = s.options.style_params.cartoon;
  const glm::vec3 th = p.band_thresholds;
  if (!f.hit) {
    float nm = smoothStep(0.6f * kReferenceIso, kReferenceIso, f.max_density);
    *sensitive |= nm > 0.0f && nm < 1.0f;
    return glm::vec4(outline_colour * nm + (1 - nm) * bg, 1.0f);
  }
  float d = std::max(glm::dot(f.normal, s.light.direction), 0.0f) * (0.35f + 0.65f * f.light_t);
  *ambiguous |= near(d, {th.x, th.y, th.z}, 0.01f);
  const glm::vec3 tones[4] = {
      {0.50f, 0.57f, 0.78f}, {0.68f, 0.75f, 0.90f}, {0.86f, 0.90f, 0.97f}, {1.0f, 1.0f, 1.0f}};
  glm::vec3 cel = tones[d < th.x ? 0 : d < th.y ? 1 : d < th.z ? 2 : 3] * s.light.colour;
  float outline =
      1 - smoothStep(0.5f * p.outline_width, p.outline_width, std::abs(glm::dot(f.normal, f.view)));
  float inner = 1 - smoothStep(0.03f, 0.06f, std::abs(f.inner_max - kReferenceInnerIso));
  *sensitive |= outlineSensitive(f);
  return glm::vec4(glm::mix(cel, outline_colour, std::max(outline, 0.8f * inner)), 1.0f);
}

// Seed 001 §3.3.3–3.3.4: the ray-cast ink amounts (wash, silhouette, 0, coverage), 8-bit.
glm::vec4 inkAmounts(const ReferenceScene& s, const Surface& f, bool* band_ambiguous,
                     bool* sensitive) {
  float nm = smoothStep(0.6f * kReferenceIso, kReferenceIso, f.max_density);
  *sensitive |= nm > 0.0f && nm < 1.0f;
  if (!f.hit) return glm::vec4(0, quantise8(nm), 0, quantise8(nm));
  float d = std::max(glm::dot(f.normal, s.light.direction), 0.0f) * (0.35f + 0.65f * f.light_t);
  float band;
  if (s.options.moving) {
    *band_ambiguous |= near(d, {0.55f}, 0.01f);
    band = d <= 0.55f ? 0.7f : 0.1f;
  } else {
    *band_ambiguous |= near(d, {0.25f, 0.55f, 0.8f}, 0.01f);
    band = d <= 0.25f ? 1.0f : d <= 0.55f ? 0.7f : d <= 0.8f ? 0.4f : 0.1f;
  }
  const InkStyleParams& p = s.options.style_params.ink;
  float edge = std::abs(glm::dot(f.normal, f.view));
  *sensitive |= outlineSensitive(f);
  float x = 3.0f * edge / p.line_width;
  float silhouette = edge < p.line_width ? std::exp(-0.5f * x * x) : 0.0f;
  return glm::vec4(quantise8(p.wash * band), quantise8(silhouette), 0, 1);
}

glm::vec4 sketchAmounts(const ReferenceScene& s, const Surface& f, bool* sensitive) {
  float nm = smoothStep(0.6f * kReferenceIso, kReferenceIso, f.max_density);
  *sensitive |= outlineSensitive(f) || (nm > 0.0f && nm < 1.0f);
  if (!f.hit) return glm::vec4(0, 0, 0, quantise8(nm));  // the near miss: coverage only
  float d = std::max(glm::dot(f.normal, s.light.direction), 0.0f) * (0.35f + 0.65f * f.light_t);
  const float width = s.options.style_params.sketch.outline_width;
  float outline = 1 - smoothStep(0.5f * width, width, std::abs(glm::dot(f.normal, f.view)));
  float inner = 1 - smoothStep(0.03f, 0.06f, std::abs(f.inner_max - kReferenceInnerIso));
  return glm::vec4(quantise8(1 - d), quantise8(std::max(outline, 0.45f * inner)), 0, 1);
}

// Screen-space noise of the paper styles: an integer hash of the pixel and its smooth
// interpolation (the same functions as the compose pass, for the same pixels).
float hash(glm::vec2 p) {
  uint32_t qx = uint32_t(int(std::floor(p.x)) + 65536), qy = uint32_t(int(std::floor(p.y)) + 65536);
  uint32_t h = (qx * 0x8da6b343u) ^ (qy * 0xd8163841u);
  h ^= h >> 13;
  h *= 0x85ebca6bu;
  h ^= h >> 16;
  return float(h & 0xffffu) / 65535.0f;
}

float valueNoise(glm::vec2 p) {
  glm::vec2 i = glm::floor(p), f = p - i;
  glm::vec2 w = f * f * (3.0f - 2.0f * f);
  float a = glm::mix(hash(i), hash(i + glm::vec2(1, 0)), w.x);
  float b = glm::mix(hash(i + glm::vec2(0, 1)), hash(i + glm::vec2(1, 1)), w.x);
  return glm::mix(a, b, w.y);
}

glm::vec3 xuanPaper(glm::vec2 p) {
  float fibres = 0.6f * valueNoise(p * glm::vec2(0.015f, 0.12f)) +
                 0.4f * valueNoise(p * glm::vec2(0.05f, 0.4f));
  return glm::vec3(0.93f, 0.90f, 0.82f) * (0.95f + 0.05f * fibres + 0.02f * hash(p));
}

// The compose pass's Gaussian blur of (g, coverage) around the pixel whose amounts are centre:
// along x into an 8-bit target (ink_bleed.frag.glsl), then along y (style_compose.frag.glsl),
// σ = screenBlurSigma of the style; unblurred while moving. amounts(i, j): the amounts of the
// pixel i, j away.
template <class Amounts>
glm::vec2 blurredLines(const ReferenceScene& s, glm::vec4 centre, Amounts amounts) {
  if (s.options.moving) return glm::vec2(centre.g, centre.a);
  const float sigma = screenBlurSigma(s.options.style, s.options.style_params);
  const int R = inkBleedRadius(sigma);
  float w[kMaxInkBleedRadius + 1];
  float sum = 0.0f;
  for (int i = 0; i <= R; ++i) {
    w[i] = std::exp(-float(i * i) / (2 * sigma * sigma));
    sum += i ? 2 * w[i] : w[i];
  }
  const float norm = 1.0f / sum;
  const int n = 2 * R + 1;
  std::vector<glm::vec2> ga(size_t(n * n));
  for (int j = -R; j <= R; ++j)
    for (int i = -R; i <= R; ++i) {
      const glm::vec4 a = amounts(i, j);
      ga[size_t((j + R) * n + i + R)] = glm::vec2(a.g, a.a);
    }
  glm::vec2 blurred(0.0f);
  for (int j = -R; j <= R; ++j) {
    glm::vec2 row(0.0f);
    for (int i = -R; i <= R; ++i) row += w[std::abs(i)] * ga[size_t((j + R) * n + i + R)];
    row *= norm;
    blurred += w[std::abs(j)] * glm::vec2(quantise8(row.x), quantise8(row.y));
  }
  return blurred * norm;
}

// The image-space outline of the paper styles: 1 where the blurred coverage crosses ½.
float coverageOutline(float blurred_coverage) {
  return 4.0f * blurred_coverage * (1.0f - blurred_coverage);
}

float hatchLines(float u, float spacing) {
  float f = std::abs(u / spacing - std::floor(u / spacing) - 0.5f) * 2.0f;
  return smoothStep(0.72f, 0.92f, f);
}

}  // namespace

ReferencePixel referencePixel(const ReferenceScene& s, int x, int y) {
  ReferencePixel out;
  const int yb = s.height - 1 - y;
  const RenderStyle style = s.options.style;
  if (!drawsIsoSurface(style)) {
    const Ray r = makeRay(s, x, yb);
    out.rgba = compositedPixel(s, r, behind(s, r, x, yb));
    return out;
  }
  auto surfaceAt = [&](int px, int py_bottom) {
    Surface f = findSurface(s, makeRay(s, px, py_bottom));
    out.ambiguous |= f.ambiguous;
    return f;
  };
  const glm::vec2 p = glm::vec2(x, yb) + 0.5f;  // gl_FragCoord
  if (style == RenderStyle::kCartoon) {
    const glm::vec3 bg(behind(s, makeRay(s, x, yb), x, yb));
    out.rgba = cartoonPixel(s, surfaceAt(x, yb), bg, &out.ambiguous, &out.sensitive);
  } else if (style == RenderStyle::kInk) {
    glm::vec4 centre = inkAmounts(s, surfaceAt(x, yb), &out.ambiguous, &out.sensitive);
    // Ink bleeding (seed 001 §3.3.5; σ² = 2, R = 3 by default). A neighbour's wash band does not
    // reach this pixel (only its silhouette ink and its coverage, for the outline, are blurred).
    bool band_ambiguous = false;
    const glm::vec2 blurred = blurredLines(s, centre, [&](int i, int j) {
      return inkAmounts(s, surfaceAt(x + i, yb + j), &band_ambiguous, &out.sensitive);
    });
    // The image-space outline (style_compose.frag.glsl): 0.6 · 4A(1 − A) of the blurred coverage.
    const float silhouette = std::max(blurred.x, 0.6f * coverageOutline(blurred.y));
    float ink = 1 - (1 - centre.r) * (1 - silhouette);
    float grey = smoothStep(0.1f, 0.92f, 1 - ink);
    out.rgba = glm::vec4(glm::mix(glm::vec3(0.07f, 0.07f, 0.09f), xuanPaper(p), grey), 1.0f);
  } else {
    glm::vec4 a = sketchAmounts(s, surfaceAt(x, yb), &out.sensitive);
    const glm::vec2 blurred = blurredLines(s, a, [&](int i, int j) {
      return sketchAmounts(s, surfaceAt(x + i, yb + j), &out.sensitive);
    });
    // The outline strokes or the image-space outline in pencil (0.9, style_compose.frag.glsl).
    const float line = std::max(a.g, 0.9f * coverageOutline(blurred.y));
    float wobble = (valueNoise(p * 0.03f) - 0.5f) * 5.0f;
    float tone = a.r;
    // The hatching fades in over tone ramps of 0.1 (slope 10): a ramp is as steep as an outline.
    auto onRamp = [&](float lo) { return tone > lo - 0.02f && tone < lo + 0.12f; };
    out.sensitive |= onRamp(0.35f) || onRamp(0.6f) || onRamp(0.85f);
    float hatch = smoothStep(0.35f, 0.45f, tone) * hatchLines(p.x + p.y + wobble, 7.0f);
    hatch = std::max(hatch, smoothStep(0.6f, 0.7f, tone) * hatchLines(p.x - p.y - wobble, 7.0f));
    hatch = std::max(hatch, smoothStep(0.85f, 0.95f, tone) * hatchLines(p.y + 0.5f * wobble, 4.0f));
    float grain = 0.65f + 0.35f * valueNoise(p * glm::vec2(0.6f, 0.08f));
    float stroke = std::max(line * (0.75f + 0.25f * grain), 0.5f * hatch * grain);
    glm::vec3 paper = glm::vec3(0.97f, 0.96f, 0.93f) * (0.97f + 0.03f * hash(p));
    out.rgba = glm::vec4(glm::mix(paper, glm::vec3(0.22f, 0.22f, 0.26f), stroke), 1.0f);
  }
  return out;
}

void packDensityAndLight(const Volume& volume, const LightVolume& light, const VoxelBox& box,
                         std::vector<uint8_t>* packed) {
  const VoxelBox b = box.intersect(volume.bounds());
  packed->clear();
  if (b.empty()) return;
  packed->reserve(size_t(b.voxelCount()) * 2);
  auto unorm8 = [](float v) { return uint8_t(std::clamp(v, 0.0f, 1.0f) * 255.0f + 0.5f); };
  for (int z = b.lo.z; z < b.hi.z; ++z)
    for (int y = b.lo.y; y < b.hi.y; ++y)
      for (int x = b.lo.x; x < b.hi.x; ++x) {
        packed->push_back(unorm8(volume.at(x, y, z)));
        packed->push_back(unorm8(light.at(x, y, z)));
      }
}

}  // namespace cb
