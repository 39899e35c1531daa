#include "stroke_measures.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "app/core/parallel_for.h"

namespace cb::test {
namespace {

constexpr float kInside = 0.5f;  // silhouette: at least half opaque (what_you_paint_test's)
constexpr float kExtinctionPerVoxel = 0.35f;  // config/render.toml [raycast]

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
  return v[v.size() / 2];
}

// Clips a ray to [lo, hi]; false when it misses.
bool clip(glm::vec3 o, glm::vec3 d, glm::vec3 lo, glm::vec3 hi, float* t0, float* t1) {
  *t0 = 0.0f;
  *t1 = 1e30f;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(d[a]) < 1e-12f) {
      if (o[a] < lo[a] || o[a] > hi[a]) return false;
      continue;
    }
    float ta = (lo[a] - o[a]) / d[a], tb = (hi[a] - o[a]) / d[a];
    if (ta > tb) std::swap(ta, tb);
    *t0 = std::max(*t0, ta);
    *t1 = std::min(*t1, tb);
  }
  return *t0 < *t1;
}

float densityAt(const Volume& v, glm::vec3 world) {
  const glm::ivec3 p(glm::floor(v.worldToVoxel(world)));
  if (!v.bounds().contains(p)) return 0.0f;
  return v.at(p.x, p.y, p.z);
}

}  // namespace

float Silhouette::at(glm::vec2 screen_px) const {
  const int x = int(std::floor(screen_px.x / float(downscale)));
  const int y = int(std::floor(screen_px.y / float(downscale)));
  if (x < 0 || y < 0 || x >= width || y >= height) return 0.0f;
  return opacity[size_t(y) * width + x];
}

Silhouette silhouetteOpacity(const Volume& volume, const VoxelBox& box, const Camera& camera,
                             int screen_w, int screen_h, int downscale, glm::ivec4 rect) {
  Silhouette s;
  s.downscale = downscale;
  s.width = screen_w / downscale;
  s.height = screen_h / downscale;
  s.opacity.assign(size_t(s.width) * s.height, 0.0f);
  const glm::vec3 lo = volume.voxelToWorld(glm::vec3(box.lo));
  const glm::vec3 hi = volume.voxelToWorld(glm::vec3(box.hi));
  const glm::vec3 vs = volume.voxelSize();
  const float step = std::min({vs.x, vs.y, vs.z});
  // The renderer's absorption: α = 1 − exp(−σ·density·step), σ per voxel step
  // (config/render.toml raycast.extinction_per_voxel).
  const float sigma_step = kExtinctionPerVoxel * step / std::min({vs.x, vs.y, vs.z});
  const int x0 = std::max(0, rect.x / downscale), y0 = std::max(0, rect.y / downscale);
  const int x1 = std::min(s.width, rect.z / downscale + 1);
  const int y1 = std::min(s.height, rect.w / downscale + 1);
  parallelFor(size_t(std::max(0, y1 - y0)), 4, [&](size_t, size_t r0, size_t r1) {
    for (size_t r = r0; r < r1; ++r) {
      const int y = y0 + int(r);
      for (int x = x0; x < x1; ++x) {
        glm::vec3 o, d;
        camera.pixelRay(float(x), float(y), s.width, s.height, &o, &d);
        float t0, t1;
        if (!clip(o, d, lo, hi, &t0, &t1)) continue;
        float optical_depth = 0.0f;
        for (float t = t0 + 0.5f * step; t < t1 && optical_depth < 10.0f; t += step)
          optical_depth += sigma_step * std::min(1.0f, densityAt(volume, o + d * t));
        s.opacity[size_t(y) * s.width + x] = 1.0f - std::exp(-optical_depth);
      }
    }
  });
  return s;
}

std::vector<glm::vec2> resamplePath(const std::vector<glm::vec2>& path, float step) {
  std::vector<glm::vec2> out;
  if (path.empty()) return out;
  out.push_back(path.front());
  float carried = 0.0f;
  for (size_t i = 1; i < path.size(); ++i) {
    const glm::vec2 a = path[i - 1], b = path[i];
    const float length = glm::length(b - a);
    float next = step - carried;
    while (next <= length) {
      out.push_back(a + (b - a) * (next / length));
      next += step;
    }
    carried = length - (next - step);
  }
  if (glm::length(out.back() - path.back()) > 1e-3f) out.push_back(path.back());
  return out;
}

PathMeasures measureAlongPath(const Silhouette& s, const std::vector<glm::vec2>& drawn,
                              bool point_like) {
  PathMeasures m;
  const float step = 2.0f, reach = 0.45f * float(s.height * s.downscale);
  const std::vector<glm::vec2> path = resamplePath(drawn, step);
  const auto edge = [&](glm::vec2 p, glm::vec2 dir) {
    float d = 0.0f;
    while (d < reach && s.at(p + dir * d) >= kInside) d += 1.0f;
    return d;
  };
  const auto stats = [](const std::vector<float>& v, double* mean, double* cv) {
    double sum = 0, sq = 0;
    for (float x : v) sum += x, sq += double(x) * x;
    *mean = v.empty() ? 0.0 : sum / double(v.size());
    const double var = v.empty() ? 0.0 : std::max(0.0, sq / double(v.size()) - *mean * *mean);
    *cv = *mean > 0.0 ? std::sqrt(var) / *mean : 0.0;
  };
  std::vector<bool> inside(path.size());
  for (size_t i = 0; i < path.size(); ++i) inside[i] = s.at(path[i]) >= kInside;
  m.ends_inside = inside.front() && inside.back() ? 1.0 : 0.0;
  if (point_like) {
    glm::dvec2 sum(0.0);
    double n = 0;
    for (int y = 0; y < s.height; ++y)
      for (int x = 0; x < s.width; ++x)
        if (s.opacity[size_t(y) * s.width + x] >= kInside)
          sum += glm::dvec2(x + 0.5, y + 0.5) * double(s.downscale), n += 1;
    if (n == 0) return m;
    const glm::vec2 c(sum / n);
    for (int k = 0; k < 64; ++k) {
      const float a = 6.2831853f * float(k) / 64.0f;
      m.half_widths.push_back(edge(c, glm::vec2(std::cos(a), std::sin(a))));
    }
    double mean;
    stats(m.half_widths, &mean, &m.cv);
    m.width_px = 2.0 * mean;
  } else {
    std::vector<double> all;
    std::vector<float> arc(path.size(), 0.0f);
    for (size_t i = 1; i < path.size(); ++i)
      arc[i] = arc[i - 1] + glm::length(path[i] - path[i - 1]);
    std::vector<float> hw(path.size(), -1.0f);
    for (size_t i = 0; i < path.size(); ++i) {
      if (!inside[i]) continue;
      const glm::vec2 t = path[std::min(i + 1, path.size() - 1)] - path[i > 0 ? i - 1 : 0];
      if (glm::length(t) <= 0.0f) continue;
      const glm::vec2 n = glm::normalize(glm::vec2(-t.y, t.x));
      hw[i] = 0.5f * (edge(path[i], n) + edge(path[i], -n));
      all.push_back(hw[i]);
    }
    m.width_px = 2.0 * median(all);
    // Billows along the body: the ends' caps (one half-width from each end) are not counted.
    const float cap = float(0.5 * m.width_px);
    for (size_t i = 0; i < path.size(); ++i)
      if (hw[i] >= 0.0f && arc[i] >= cap && arc.back() - arc[i] >= cap)
        m.half_widths.push_back(hw[i]);
    double mean;
    stats(m.half_widths, &mean, &m.cv);
  }
  // A break is where the cloud is missing, not where the pen's centre line runs along the edge
  // of a thin cloud (a light touch's ink lies to one side of the nib's path): a path point
  // counts as covered when cloud lies within a quarter of the stroke's width of it.
  const float near = 0.25f * float(m.width_px);
  const auto covered = [&](size_t i) {
    if (inside[i]) return true;
    for (float r = 1.0f; r <= near; r += 1.0f)
      for (int k = 0; k < 16; ++k) {
        const float a = 6.2831853f * float(k) / 16.0f;
        if (s.at(path[i] + r * glm::vec2(std::cos(a), std::sin(a))) >= kInside) return true;
      }
    return false;
  };
  size_t run = 0, widest = 0;
  for (size_t i = 0; i < path.size(); ++i) {
    run = covered(i) ? 0 : run + 1;
    widest = std::max(widest, run);
  }
  m.widest_gap = m.width_px > 0.0 ? double(widest) * step / m.width_px : 1.0;
  const auto shortfall = [&](glm::vec2 end) {
    if (s.at(end) >= kInside) return 0.0;
    for (float r = 1.0f; r <= float(m.width_px); r += 1.0f)
      for (int k = 0; k < 64; ++k) {
        const float a = 6.2831853f * float(k) / 64.0f;
        if (s.at(end + r * glm::vec2(std::cos(a), std::sin(a))) >= kInside)
          return double(r) / m.width_px;
      }
    return 1.0;
  };
  m.end_shortfall =
      m.width_px > 0.0 ? std::max(shortfall(path.front()), shortfall(path.back())) : 1.0;
  return m;
}

double bodyRatio(const Volume& v, const Camera& camera, const Canvas& canvas, int sw, int sh,
                 const std::vector<glm::vec2>& drawn, bool point_like, float threshold) {
  const std::vector<glm::vec2> path = resamplePath(drawn, 8.0f);
  std::vector<glm::vec3> on_plane;
  for (glm::vec2 p : path) {
    glm::vec3 o, d;
    camera.pixelRay(p.x, p.y, sw, sh, &o, &d);
    float t = 0.0f;
    if (canvas.intersectMidPlane(o, d, &t)) on_plane.push_back(o + d * t);
  }
  const glm::vec3 vs = v.voxelSize();
  const glm::ivec3 dims = v.dims();
  std::vector<double> thickness, width;
  for (size_t i = 0; i < on_plane.size(); ++i) {
    const glm::ivec3 c(glm::floor(v.worldToVoxel(on_plane[i])));
    if (c.x < 0 || c.z < 0 || c.x >= dims.x || c.z >= dims.z) continue;
    int best = -1;
    for (int y = 0; y < dims.y; ++y)
      if (best < 0 || v.at(c.x, y, c.z) > v.at(c.x, best, c.z)) best = y;
    if (v.at(c.x, best, c.z) <= threshold) continue;
    int lo = best, hi = best;
    while (lo > 0 && v.at(c.x, lo - 1, c.z) > threshold) --lo;
    while (hi + 1 < dims.y && v.at(c.x, hi + 1, c.z) > threshold) ++hi;
    thickness.push_back(double(hi - lo + 1) * vs.y);
    glm::vec3 centre = v.voxelToWorld(glm::vec3(c) + 0.5f);
    centre.y = v.voxelToWorld(glm::vec3(0.0f, 0.5f * float(lo + hi + 1), 0.0f)).y;
    std::vector<glm::vec3> across;
    if (point_like || on_plane.size() < 2) {
      across = {{1, 0, 0}, {0, 0, 1}};
    } else {
      const glm::vec3 t =
          on_plane[std::min(i + 1, on_plane.size() - 1)] - on_plane[i > 0 ? i - 1 : 0];
      across = {glm::normalize(glm::vec3(-t.z, 0.0f, t.x))};
    }
    double w = 0.0;
    for (glm::vec3 n : across) {
      const float stepw = vs.x;
      float a = 0.0f, b = 0.0f;
      while (a < 2.0f && densityAt(v, centre + n * a) > threshold) a += stepw;
      while (b < 2.0f && densityAt(v, centre - n * b) > threshold) b += stepw;
      w += double(a + b) / double(across.size());
    }
    width.push_back(w);
  }
  const double wm = median(width);
  return wm > 0.0 ? median(thickness) / wm : 0.0;
}

}  // namespace cb::test
