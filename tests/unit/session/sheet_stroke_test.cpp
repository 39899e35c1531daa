// The sheet stroke through the session at product defaults (256³ sky, default brush and mapping
// config, the default paint view): a broad stroke lays a wide, thin, flat layer on the canvas
// (thesis §7.7.5 problem 1), covering the ink as seen from the paint view, the same on any thread
// count.
#include <gtest/gtest.h>

#include "app/core/config_paths.h"
#include "app/core/parallel_for.h"
#include "app/session/paint_session.h"
#include "app/session/session_replay.h"
#include "app/session/synthetic_session.h"

namespace cb {
namespace {

constexpr int kW = 1280, kH = 720;

struct Painted {
  uint64_t checksum = 0;
  glm::ivec3 lo{1 << 20}, hi{-1};
  double ink_covered = 0;  // fraction of inked footprint pixels whose ray meets the layer
};

Painted paintSheet(int threads) {
  setWorkerThreads(threads);
  PaintSession session({kW, kH, 256}, loadDefaultBrushConfig(),
                       loadMappingConfig(configFile("mapping.toml")));
  session.setQuietMapping(true);
  const PenDeviceInfo tablet = syntheticTablet(kW, kH);
  session.setDevice(tablet, 0);
  std::string error;
  EXPECT_TRUE(session.apply(ui::SetMapping{MappingMethod::kSheet}, 0, &error)) << error;
  SyntheticStroke broad;
  broad.control_points = {
      {0.25f * kW, 0.5f * kH}, {0.5f * kW, 0.45f * kH}, {0.75f * kW, 0.55f * kH}};
  broad.pressure = [](float) { return 1.0f; };
  Footprint ink;
  for (const PenSample& s : syntheticPenSamples(broad, tablet, kW, kH, 200.0, 1'000'000'000)) {
    if (session.engine().inStroke()) ink = session.engine().footprint();
    session.feed(s);
  }
  EXPECT_EQ(session.strokesMapped(), 1u);
  Painted p;
  const Volume& v = session.volume();
  p.checksum = volumeChecksum(v);
  for (int z = 0; z < v.dims().z; ++z)
    for (int y = 0; y < v.dims().y; ++y)
      for (int x = 0; x < v.dims().x; ++x)
        if (v.at(x, y, z) > 0.02f) {
          p.lo = glm::min(p.lo, glm::ivec3(x, y, z));
          p.hi = glm::max(p.hi, glm::ivec3(x, y, z));
        }
  // Each inked pixel's ray, marched through the volume, meets the layer.
  long long inked = 0, covered = 0;
  for (int py = 0; py < ink.height; py += 4)
    for (int px = 0; px < ink.width; px += 4) {
      if (!(ink.at(px, py) > 0.2f)) continue;
      ++inked;
      glm::vec3 o, d;
      // Footprint pixel (px, py) is the ray through it of a footprint-sized image (PaintView).
      session.camera().pixelRay(float(px), float(py), ink.width, ink.height, &o, &d);
      float tau = 0;
      for (float t = 0; t < 8.0f; t += 0.004f) {
        const glm::vec3 q = v.worldToVoxel(o + t * d);
        const glm::ivec3 i(glm::floor(q));
        if (glm::all(glm::greaterThanEqual(i, glm::ivec3(0))) &&
            glm::all(glm::lessThan(i, v.dims())))
          tau += v.at(i.x, i.y, i.z);
      }
      covered += tau > 0.5f;
    }
  p.ink_covered = inked ? double(covered) / double(inked) : 0.0;
  setWorkerThreads(0);
  return p;
}

TEST(SheetStroke, ABroadStrokeLaysAWideThinFlatLayer) {
  const Painted one = paintSheet(1);
  const glm::ivec3 extent = one.hi - one.lo + 1;
  std::printf("sheet layer: %d x %d x %d voxels, %.1f%% of the ink covered\n", extent.x, extent.y,
              extent.z, 100.0 * one.ink_covered);
  EXPECT_GT(extent.x, 60);
  EXPECT_LE(extent.y, 14) << "thin: within ±3σ of the canvas plane";
  EXPECT_GT(std::max(extent.x, extent.z), 8 * extent.y) << "flat";
  EXPECT_GE(one.ink_covered, 0.9);
  EXPECT_EQ(paintSheet(8).checksum, one.checksum) << "the same volume on 1 and 8 threads";
}

}  // namespace
}  // namespace cb
