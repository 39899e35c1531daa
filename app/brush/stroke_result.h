// What a finished stroke hands from the brushes to the mapping (thesis ch. 5 -> ch. 6).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "app/scene/camera.h"
#include "app/scene/canvas.h"
#include "drivers/core/pen_sample.h"

namespace cb {

// A 2D float buffer in the paint view's screen space: row-major, row 0 at the top, values 0..1.
struct Footprint {
  int width = 0, height = 0;
  std::vector<float> values;

  Footprint() = default;
  Footprint(int w, int h) : width(w), height(h), values(size_t(w) * h, 0.0f) {}
  float at(int x, int y) const { return values[size_t(y) * width + x]; }
  float& at(int x, int y) { return values[size_t(y) * width + x]; }
  bool inside(int x, int y) const { return x >= 0 && y >= 0 && x < width && y < height; }
};

// The camera the stroke was painted from; footprint pixel (x, y) is the camera's pixel ray
// through (x, y) of a footprint.width × footprint.height image (Camera::pixelRay).
struct PaintView {
  Camera camera;
};

enum class BrushKind : uint8_t { k2D = 0, k3D = 1, kSkeleton = 2 };

// One point of the stroke's path as the brush consumed it.
struct StrokePoint {
  glm::vec2 footprint_px;  // position in footprint pixels
  float pressure = 0.0f;   // after calibration, 0..1
  float tilt_x_deg = 0.0f, tilt_y_deg = 0.0f;
  int64_t t_ns = 0;
};

struct StrokeResult {
  uint32_t stroke_index = 0;  // seeds all randomness of brush and mapping for this stroke
  BrushKind brush = BrushKind::k3D;
  Footprint footprint;
  PaintView view;
  Canvas canvas;
  std::vector<StrokePoint> path;    // what the brush consumed, in order
  std::vector<PenSample> raw_path;  // the raw samples of the stroke (for analysis)
};

}  // namespace cb
