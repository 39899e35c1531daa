#include "app/shell/painter/hud_items.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <utility>

namespace cb {
namespace {

// 3×5 glyphs, one row per 3 bits (bit 2 = left column), top row first.
std::array<uint8_t, 5> glyph(char c) {
  switch (c) {
    case '0':
      return {7, 5, 5, 5, 7};
    case '1':
      return {2, 6, 2, 2, 7};
    case '2':
      return {7, 1, 7, 4, 7};
    case '3':
      return {7, 1, 7, 1, 7};
    case '4':
      return {5, 5, 7, 1, 1};
    case '5':
      return {7, 4, 7, 1, 7};
    case '6':
      return {7, 4, 7, 5, 7};
    case '7':
      return {7, 1, 1, 1, 1};
    case '8':
      return {7, 5, 7, 5, 7};
    case '9':
      return {7, 5, 7, 1, 7};
    case '.':
      return {0, 0, 0, 0, 2};
    case '-':
      return {0, 0, 7, 0, 0};
    default:
      return {0, 0, 0, 0, 0};
  }
}

}  // namespace

StatsPanelLayout statsPanelLayout(int /*screen_width*/, int screen_height) {
  StatsPanelLayout layout;
  layout.baseline_y = screen_height - 24;
  return layout;
}

std::vector<int> statsBarHeights(const std::vector<uint32_t>& histogram, int max_height) {
  uint32_t fullest = 0;
  for (uint32_t count : histogram) fullest = std::max(fullest, count);
  std::vector<int> heights(histogram.size(), 0);
  if (fullest == 0) return heights;
  for (size_t i = 0; i < histogram.size(); ++i)
    heights[i] = int(std::lround(double(histogram[i]) / double(fullest) * max_height));
  return heights;
}

void appendHudText(const std::string& text, int x, int y, int cell, glm::vec4 colour,
                   std::vector<HudItem>* items) {
  for (char c : text) {
    const std::array<uint8_t, 5> rows = glyph(c);
    for (int row = 0; row < 5; ++row)
      for (int col = 0; col < 3; ++col)
        if (rows[size_t(row)] & (4 >> col))
          items->push_back(makeHudRect(float(x + col * cell), float(y + row * cell),
                                       float(x + (col + 1) * cell), float(y + (row + 1) * cell),
                                       colour));
    x += 4 * cell;
  }
}

void appendStatsPanel(const RenderStats& stats, int screen_width, int screen_height,
                      std::vector<HudItem>* items) {
  if (!stats.has_samples || stats.histogram.empty()) return;
  const StatsPanelLayout layout = statsPanelLayout(screen_width, screen_height);
  const int bins = int(stats.histogram.size());
  const int cell = 3, line = 6 * cell;
  const int text_top = layout.baseline_y - layout.max_height - 3 * line - 8;
  // A dark backing so bars and digits read over a bright sky.
  items->push_back(makeHudRect(float(layout.left - 8), float(text_top - 8),
                               float(layout.left + bins * layout.bar_pitch + 8),
                               float(layout.baseline_y + 8), {0.0f, 0.0f, 0.0f, 0.55f}));
  const std::vector<int> heights = statsBarHeights(stats.histogram, layout.max_height);
  for (int i = 0; i < bins; ++i) {
    if (heights[size_t(i)] == 0) continue;
    const int x0 = layout.left + i * layout.bar_pitch;
    items->push_back(makeHudRect(float(x0), float(layout.baseline_y - heights[size_t(i)]),
                                 float(x0 + layout.bar_width), float(layout.baseline_y),
                                 kHudBarColour));
  }
  // Rows: total samples, mean per pixel, max per pixel (colour swatches tell them apart).
  char total[32], mean[32], max[32];
  std::snprintf(total, sizeof total, "%llu", static_cast<unsigned long long>(stats.samples_total));
  std::snprintf(mean, sizeof mean, "%.1f", stats.samples_mean);
  std::snprintf(max, sizeof max, "%u", stats.samples_max);
  const glm::vec4 swatches[3] = {{0.4f, 0.8f, 1.0f, 1.0f}, kHudBarColour, {1.0f, 0.4f, 0.3f, 1.0f}};
  const char* rows[3] = {total, mean, max};
  for (int r = 0; r < 3; ++r) {
    const int y = text_top + r * line;
    items->push_back(makeHudRect(float(layout.left), float(y), float(layout.left + 3 * cell),
                                 float(y + 5 * cell), swatches[r]));
    appendHudText(rows[r], layout.left + 5 * cell, y, cell, kHudDigitColour, items);
  }
}

glm::vec2 footprintToScreen(glm::vec2 footprint_px, int footprint_w, int footprint_h, int screen_w,
                            int screen_h) {
  const glm::vec2 scale(float(screen_w) / float(std::max(footprint_w, 1)),
                        float(screen_h) / float(std::max(footprint_h, 1)));
  return (footprint_px + 0.5f) * scale;
}

void appendCircleRings(const std::vector<Circle>& circles, int footprint_w, int footprint_h,
                       int screen_w, int screen_h, std::vector<HudItem>* items) {
  const float scale = float(screen_w) / float(std::max(footprint_w, 1));
  for (const Circle& circle : circles)
    items->push_back(
        makeHudRing(footprintToScreen(circle.centre, footprint_w, footprint_h, screen_w, screen_h),
                    float(circle.radius) * scale, 2.0f, kHudRingColour));
}

std::vector<glm::vec2> canvasRegionOutline(const Camera& camera, const Canvas& canvas,
                                           glm::vec3 world_min, glm::vec3 world_max, int screen_w,
                                           int screen_h) {
  // The slab altitude ± thickness/2 (§3.4) clipped to the volume's world box.
  const float y0 = std::max(canvas.bottom(), world_min.y);
  const float y1 = std::min(canvas.top(), world_max.y);
  if (!(y1 > y0) || screen_w <= 0 || screen_h <= 0) return {};
  const glm::mat4 view_proj = camera.projection(float(screen_w) / float(screen_h)) * camera.view();
  std::vector<glm::vec2> points;
  for (int i = 0; i < 8; ++i) {
    const glm::vec3 corner((i & 1) ? world_max.x : world_min.x, (i & 2) ? y1 : y0,
                           (i & 4) ? world_max.z : world_min.z);
    const glm::vec4 clip = view_proj * glm::vec4(corner, 1.0f);
    if (clip.w <= camera.near_plane) return {};  // a corner behind the eye: no simple outline
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;
    points.push_back(
        {(ndc.x * 0.5f + 0.5f) * float(screen_w), (0.5f - ndc.y * 0.5f) * float(screen_h)});
  }
  // Convex hull (Andrew's monotone chain).
  std::sort(points.begin(), points.end(),
            [](glm::vec2 a, glm::vec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  const auto cross = [](glm::vec2 o, glm::vec2 a, glm::vec2 b) {
    return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
  };
  std::vector<glm::vec2> hull(2 * points.size());
  size_t k = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], points[i]) <= 0.0f) --k;
    hull[k++] = points[i];
  }
  for (size_t i = points.size() - 1, lower = k + 1; i > 0; --i) {
    while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i - 1]) <= 0.0f) --k;
    hull[k++] = points[i - 1];
  }
  hull.resize(k > 0 ? k - 1 : 0);
  return hull;
}

void appendCanvasOutline(const std::vector<glm::vec2>& outline, std::vector<HudItem>* items) {
  for (size_t i = 0; i < outline.size(); ++i)
    items->push_back(
        makeHudSegment(outline[i], outline[(i + 1) % outline.size()], 1.5f, kHudCanvasColour));
}

}  // namespace cb

namespace cb {

void appendOutsideVeil(const DrawableRegion& region, std::vector<HudItem>* items) {
  const glm::vec4 veil(0.05f, 0.05f, 0.12f, 0.45f);
  const int w = region.width(), h = region.height(), band = 4;
  for (int y = 0; y < h; y += band) {
    const int y1 = std::min(h, y + band);
    int x0 = 0, x1 = 0;
    if (!region.rowSpan(std::min(h - 1, y + band / 2), &x0, &x1)) {
      items->push_back(makeHudRect(0.0f, float(y), float(w), float(y1), veil));
      continue;
    }
    if (x0 > 0) items->push_back(makeHudRect(0.0f, float(y), float(x0), float(y1), veil));
    if (x1 + 1 < w)
      items->push_back(makeHudRect(float(x1 + 1), float(y), float(w), float(y1), veil));
  }
}

}  // namespace cb

namespace cb {

void appendCanvasGrid(const Canvas& canvas, glm::vec3 box_min, glm::vec3 box_max, int divisions,
                      const std::function<glm::vec2(glm::vec3)>& to_screen,
                      std::vector<HudItem>* items) {
  const glm::vec4 colour(1.0f, 1.0f, 1.0f, 0.22f);
  const float y = canvas.altitude;
  if (y < box_min.y || y > box_max.y || divisions < 1) return;
  const auto at = [&](int i, int j) {  // grid point (i, j) of the mid-plane
    return glm::vec3(box_min.x + float(i) / float(divisions) * (box_max.x - box_min.x), y,
                     box_min.z + float(j) / float(divisions) * (box_max.z - box_min.z));
  };
  // Each line cell by cell, so a line reaching behind the camera (the eye above a wide sky)
  // keeps the cells in front of it.
  for (int i = 0; i <= divisions; ++i)
    for (int j = 0; j < divisions; ++j) {
      const glm::vec2 pairs[2][2] = {{to_screen(at(i, j)), to_screen(at(i, j + 1))},
                                     {to_screen(at(j, i)), to_screen(at(j + 1, i))}};
      for (const auto& p : pairs)
        if (p[0].x > -1e5f && p[1].x > -1e5f)  // both ends in front of the camera
          items->push_back(makeHudSegment(p[0], p[1], 1.0f, colour));
    }
}

}  // namespace cb

namespace cb {

void appendAxisPlaneGrids(glm::vec3 centre, glm::vec3 box_min, glm::vec3 box_max, int divisions,
                          const std::function<glm::vec2(glm::vec3)>& to_screen,
                          std::vector<HudItem>* items) {
  if (divisions < 1) return;
  const glm::vec4 colours[3] = {
      {1.0f, 0.45f, 0.4f, 0.35f}, {0.45f, 1.0f, 0.5f, 0.35f}, {0.45f, 0.6f, 1.0f, 0.35f}};
  for (int axis = 0; axis < 3; ++axis) {
    if (centre[axis] < box_min[axis] || centre[axis] > box_max[axis]) continue;
    // The plane's two other axes: lines along each, at every division of the other.
    const int a = (axis + 1) % 3, b = (axis + 2) % 3;
    for (int i = 0; i <= divisions; ++i) {
      const float f = float(i) / float(divisions);
      for (const auto& [along, across] : {std::pair{a, b}, std::pair{b, a}}) {
        glm::vec3 p0 = centre, p1 = centre;
        p0[across] = p1[across] = box_min[across] + f * (box_max[across] - box_min[across]);
        p0[along] = box_min[along];
        p1[along] = box_max[along];
        const glm::vec2 s0 = to_screen(p0), s1 = to_screen(p1);
        if (s0.x > -1e5f && s1.x > -1e5f)
          items->push_back(makeHudSegment(s0, s1, 1.0f, colours[axis]));
      }
    }
  }
}

}  // namespace cb
