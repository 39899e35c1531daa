#include "app/mapping/reference_strokes.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "app/mapping/stroke_random.h"

namespace cb {
namespace {

glm::vec2 catmullRom(glm::vec2 p0, glm::vec2 p1, glm::vec2 p2, glm::vec2 p3, float t) {
  float t2 = t * t, t3 = t2 * t;
  return 0.5f * ((2.0f * p1) + (-p0 + p2) * t + (2.0f * p0 - 5.0f * p1 + 4.0f * p2 - p3) * t2 +
                 (-p0 + 3.0f * p1 - 3.0f * p2 + p3) * t3);
}

// Smooth 1D value noise over the lateral coordinate u in [-1, 1]: a bristle-density pattern.
class BristlePattern {
 public:
  explicit BristlePattern(uint32_t seed) {
    StrokeRandom rng(seed, 0xB415u);
    for (float& v : values_) v = float(rng.uniform());
  }
  float operator()(float u) const {
    float x = (u + 1.0f) * 0.5f * float(kCells - 1);
    int i = std::clamp(int(x), 0, kCells - 2);
    float f = x - float(i);
    f = f * f * (3.0f - 2.0f * f);
    return values_[i] * (1.0f - f) + values_[i + 1] * f;
  }

 private:
  static constexpr int kCells = 48;
  float values_[kCells];
};

}  // namespace

Camera referencePaintCamera() {
  Camera c = Camera::reference();
  c.eye = c.target + (c.eye - c.target) * 0.58f;
  return c;
}

void splatReferencePath(const ReferencePath& path, const ReferenceBrush& brush, uint32_t seed,
                        Footprint* fp, std::vector<StrokePoint>* consumed) {
  const size_t n = path.points.size();
  if (n == 0) return;
  const BristlePattern bristles(seed);
  // Dense polyline along the spline with its pressure and tilt.
  struct Dense {
    glm::vec2 p;
    float pressure, tilt;
  };
  std::vector<Dense> dense;
  for (size_t i = 0; i + 1 < n || (n == 1 && i == 0); ++i) {
    if (n == 1) {
      dense.push_back({path.points[0], path.pressure[0], path.tilt_deg[0]});
      break;
    }
    glm::vec2 p0 = path.points[i ? i - 1 : 0], p1 = path.points[i], p2 = path.points[i + 1],
              p3 = path.points[std::min(n - 1, i + 2)];
    for (int s = 0; s < 64; ++s) {
      float t = float(s) / 64.0f;
      dense.push_back({catmullRom(p0, p1, p2, p3, t),
                       glm::mix(path.pressure[i], path.pressure[i + 1], t),
                       glm::mix(path.tilt_deg[i], path.tilt_deg[i + 1], t)});
    }
  }
  if (n > 1) dense.push_back({path.points[n - 1], path.pressure[n - 1], path.tilt_deg[n - 1]});

  // Resample at the brush spacing and splat.
  float carried = 0.0f;
  for (size_t i = 0; i < dense.size(); ++i) {
    glm::vec2 dir = i + 1 < dense.size() ? dense[i + 1].p - dense[i].p : glm::vec2(1, 0);
    float len = glm::length(dir);
    if (i + 1 < dense.size() && carried > 0.0f && carried + len < brush.spacing_px) {
      carried += len;
      continue;
    }
    carried = 0.0f;
    glm::vec2 tangent = len > 1e-6f ? dir / len : glm::vec2(1, 0);
    glm::vec2 normal(-tangent.y, tangent.x);
    const Dense& d = dense[i];
    const float pressure = std::clamp(d.pressure, 0.0f, 1.0f);
    const float r = std::max(1.0f, brush.max_radius_px * pressure);
    const float tilt_stretch = std::sin(glm::radians(d.tilt));
    consumed->push_back({d.p, pressure, d.tilt, 0.0f, int64_t(consumed->size()) * 2500000});
    const float reach = r * (1.0f + std::abs(tilt_stretch)) + brush.soft_edge_px;
    for (int y = std::max(0, int(d.p.y - reach)); y <= std::min(fp->height - 1, int(d.p.y + reach));
         ++y)
      for (int x = std::max(0, int(d.p.x - reach));
           x <= std::min(fp->width - 1, int(d.p.x + reach)); ++x) {
        glm::vec2 q = glm::vec2(float(x), float(y)) - d.p;
        float lateral = glm::dot(q, normal);
        // Tilt widens the side the pen leans towards.
        float side_r = r * (1.0f + (lateral * tilt_stretch > 0.0f ? std::abs(tilt_stretch) : 0.0f));
        float along = glm::dot(q, tangent);
        float dist = std::sqrt(along * along + lateral * lateral * (r * r) / (side_r * side_r));
        float v = std::clamp((r - dist) / brush.soft_edge_px, 0.0f, 1.0f);
        if (v <= 0.0f) continue;
        // Bristles: in the outer zone, ink thins into streaks along the path.
        float u = std::clamp(lateral / side_r, -1.0f, 1.0f);
        float outer = std::clamp((std::abs(u) - (1.0f - brush.bristle_zone)) / brush.bristle_zone,
                                 0.0f, 1.0f);
        v *= 1.0f - outer * (1.0f - bristles(u)) * 1.2f;
        v = std::clamp(v, 0.0f, 1.0f);
        float& dst = fp->at(x, y);
        dst = std::max(dst, v);
      }
  }
}

StrokeResult makeThickStroke(int width, int height, uint32_t seed) {
  StrokeResult s;
  s.stroke_index = seed;
  s.brush = BrushKind::k3D;
  s.footprint = Footprint(width, height);
  s.view.camera = referencePaintCamera();
  const float w = float(width), h = float(height);
  ReferencePath path;
  path.points = {{0.13f * w, 0.65f * h}, {0.22f * w, 0.52f * h}, {0.36f * w, 0.47f * h},
                 {0.50f * w, 0.55f * h}, {0.63f * w, 0.63f * h}, {0.77f * w, 0.58f * h},
                 {0.87f * w, 0.47f * h}};
  path.pressure = {0.35f, 0.8f, 1.0f, 0.75f, 0.95f, 0.7f, 0.3f};
  path.tilt_deg = {0.0f, 10.0f, 20.0f, 15.0f, 5.0f, -10.0f, 0.0f};
  ReferenceBrush brush;
  brush.max_radius_px = 0.1f * h;
  brush.soft_edge_px = std::max(1.5f, 0.004f * h);
  brush.spacing_px = std::max(1.0f, 0.003f * h);
  splatReferencePath(path, brush, seed, &s.footprint, &s.path);
  return s;
}

StrokeResult makeHeart(int width, int height, uint32_t seed) {
  StrokeResult s;
  s.stroke_index = seed;
  s.brush = BrushKind::k3D;
  s.footprint = Footprint(width, height);
  s.view.camera = referencePaintCamera();
  const float w = float(width), h = float(height);
  ReferenceBrush brush;
  brush.max_radius_px = 0.06f * h;
  brush.bristle_zone = 0.8f;
  brush.soft_edge_px = std::max(1.5f, 0.004f * h);
  brush.spacing_px = std::max(1.0f, 0.003f * h);
  // Outline loops shrinking inwards, then crossing flows through the middle (Fig. 6.9's green
  // line), so the union is a filled heart.
  const glm::vec2 centre(0.5f * w, 0.55f * h);
  const float scale = 0.0165f * h;
  for (int loop = 0; loop < 5; ++loop) {
    ReferencePath p;
    float k = 1.0f - 0.17f * float(loop);
    for (int i = 0; i <= 32; ++i) {
      float t = 2.0f * std::numbers::pi_v<float> * float(i) / 32.0f;
      float x = 16.0f * std::pow(std::sin(t), 3.0f);
      float y =
          13.0f * std::cos(t) - 5.0f * std::cos(2 * t) - 2.0f * std::cos(3 * t) - std::cos(4 * t);
      p.points.push_back(centre + glm::vec2(x, -y) * scale * k * glm::vec2(1.6f, 1.0f));
      p.pressure.push_back(0.75f + 0.25f * std::sin(3.0f * t + float(loop)));
      p.tilt_deg.push_back(15.0f * std::cos(t));
    }
    splatReferencePath(p, brush, seed + uint32_t(loop), &s.footprint, &s.path);
  }
  ReferencePath cross;
  cross.points = {centre + glm::vec2(-0.2f * w, -0.12f * h), centre + glm::vec2(0.0f, 0.1f * h),
                  centre + glm::vec2(0.2f * w, -0.12f * h)};
  cross.pressure = {0.8f, 1.0f, 0.8f};
  cross.tilt_deg = {0.0f, 0.0f, 0.0f};
  splatReferencePath(cross, brush, seed + 7u, &s.footprint, &s.path);
  return s;
}

}  // namespace cb
