#include "app/scene/drawable_region.h"

#include <algorithm>
#include <cmath>

namespace cb {

DrawableRegion::DrawableRegion(const Camera& camera, const Canvas& canvas, glm::vec3 box_min,
                               glm::vec3 box_max, int width, int height)
    : width_(std::max(width, 0)),
      height_(std::max(height, 0)),
      eye_(camera.eye),
      altitude_(canvas.altitude),
      near_plane_(camera.near_plane),
      lo_(box_min.x, box_min.z),
      hi_(box_max.x, box_max.z),
      altitude_inside_(canvas.altitude >= box_min.y && canvas.altitude <= box_max.y) {
  // The camera basis of glm::lookAt, as Camera::pixelRay inverts it.
  const glm::vec3 f = glm::normalize(camera.target - camera.eye);
  const glm::vec3 r = glm::normalize(glm::cross(f, camera.up));
  const glm::vec3 u = glm::cross(r, f);
  const float w = float(std::max(width_, 1)), h = float(std::max(height_, 1));
  const float tan_y = std::tan(glm::radians(camera.fov_y_deg) * 0.5f), tan_x = tan_y * w / h;
  // ndc_x = 2·sx/w − 1, ndc_y = 1 − 2·sy/h; direction = f + ndc_x·tan_x·r + ndc_y·tan_y·u.
  dir0_ = f - tan_x * r + tan_y * u;
  dir_x_ = (2.0f * tan_x / w) * r;
  dir_y_ = (-2.0f * tan_y / h) * u;

  if (!altitude_inside_) return;
  // The mid-plane rectangle, clipped to the half-space in front of the near plane
  // (Sutherland–Hodgman against one plane), then projected.
  const glm::vec3 corners[4] = {{lo_.x, altitude_, lo_.y},
                                {hi_.x, altitude_, lo_.y},
                                {hi_.x, altitude_, hi_.y},
                                {lo_.x, altitude_, hi_.y}};
  const auto depth = [&](glm::vec3 p) { return glm::dot(p - eye_, f) - near_plane_; };
  std::vector<glm::vec3> clipped;
  for (int i = 0; i < 4; ++i) {
    const glm::vec3 a = corners[i], b = corners[(i + 1) % 4];
    const float da = depth(a), db = depth(b);
    if (da >= 0.0f) clipped.push_back(a);
    if ((da >= 0.0f) != (db >= 0.0f)) clipped.push_back(a + (b - a) * (da / (da - db)));
  }
  for (const glm::vec3& p : clipped) {
    const glm::vec3 q = p - eye_;
    const float d = std::max(glm::dot(q, f), near_plane_);
    const float ndc_x = glm::dot(q, r) / (d * tan_x), ndc_y = glm::dot(q, u) / (d * tan_y);
    outline_.push_back({(ndc_x * 0.5f + 0.5f) * w, (0.5f - ndc_y * 0.5f) * h});
  }
}

bool DrawableRegion::canLandAt(glm::vec2 s) const {
  if (!altitude_inside_) return false;
  const glm::vec3 d = dir0_ + s.x * dir_x_ + s.y * dir_y_;
  // The plane parameter of an unnormalised direction with unit view-axis component is the
  // view depth of the hit; it must lie beyond the near plane (so also in front of the eye).
  const float t = (altitude_ - eye_.y) / d.y;  // ±inf or NaN when parallel: fails below
  if (!(t >= near_plane_) || !std::isfinite(t)) return false;
  const float x = eye_.x + t * d.x, z = eye_.z + t * d.z;
  return x >= lo_.x && x <= hi_.x && z >= lo_.y && z <= hi_.y;
}

bool DrawableRegion::rowSpan(int y, int* x0, int* x1) const {
  if (outline_.size() < 3 || y < 0 || y >= height_) return false;
  const float sy = float(y) + 0.5f;
  float lo = INFINITY, hi = -INFINITY;
  for (size_t i = 0; i < outline_.size(); ++i) {
    const glm::vec2 a = outline_[i], b = outline_[(i + 1) % outline_.size()];
    if ((a.y > sy) == (b.y > sy)) continue;  // the row's centre line does not cross this edge
    const float x = a.x + (b.x - a.x) * ((sy - a.y) / (b.y - a.y));
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  if (!(hi >= lo)) return false;
  // Pixels whose centre x + 0.5 lies in [lo, hi].
  const float first = std::ceil(lo - 0.5f), last = std::floor(hi - 0.5f);
  if (last < 0.0f || first > float(width_ - 1) || last < first) return false;
  *x0 = int(std::max(first, 0.0f));
  *x1 = int(std::min(last, float(width_ - 1)));
  return true;
}

std::vector<uint8_t> DrawableRegion::mask() const {
  std::vector<uint8_t> m(size_t(width_) * size_t(height_), 0);
  for (int y = 0; y < height_; ++y) {
    int x0, x1;
    if (rowSpan(y, &x0, &x1))
      std::fill(m.begin() + size_t(y) * width_ + x0, m.begin() + size_t(y) * width_ + x1 + 1,
                uint8_t(1));
  }
  return m;
}

long long DrawableRegion::landablePixels() const {
  long long n = 0;
  for (int y = 0; y < height_; ++y) {
    int x0, x1;
    if (rowSpan(y, &x0, &x1)) n += x1 - x0 + 1;
  }
  return n;
}

double DrawableRegion::fillFraction() const {
  const double all = double(width_) * double(height_);
  return all > 0.0 ? double(landablePixels()) / all : 0.0;
}

}  // namespace cb
