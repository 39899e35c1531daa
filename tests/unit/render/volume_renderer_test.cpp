#include "app/render/volume_renderer.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <random>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "app/render/changed_region.h"
#include "app/volume/scene_generators.h"
#include "tests/support/test_seed.h"
#include "tests/unit/render/gl_test_context.h"

namespace cb {
namespace {

constexpr int kW = 320, kH = 200;

ImageRgba8 renderImage(VolumeRenderer& r, const Camera& cam, const RenderOptions& opt) {
  RenderTarget target;
  std::string err;
  EXPECT_TRUE(target.create(kW, kH, RenderTarget::Format::kRgba8, &err)) << err;
  r.render(cam, kW, kH, target.fbo(), opt);
  return target.readRgba8();
}

int maxChannelDifference(const ImageRgba8& a, const ImageRgba8& b) {
  int m = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i) m = std::max(m, std::abs(a.pixels[i] - b.pixels[i]));
  return m;
}

uint8_t unorm(float v) {
  return uint8_t(std::lround(v * 255.0f));
}

bool isBackground(const uint8_t* p, const RenderOptions& opt) {
  return std::abs(p[0] - unorm(opt.background.r)) <= 1 &&
         std::abs(p[1] - unorm(opt.background.g)) <= 1 &&
         std::abs(p[2] - unorm(opt.background.b)) <= 1;
}

// Pixel (row 0 at the top) where world point w projects.
glm::ivec2 project(const Camera& cam, glm::vec3 w) {
  glm::vec4 c = cam.projection(float(kW) / kH) * cam.view() * glm::vec4(w, 1.0f);
  glm::vec2 ndc = glm::vec2(c) / c.w;
  return glm::ivec2(int((ndc.x * 0.5f + 0.5f) * kW), int((0.5f - ndc.y * 0.5f) * kH));
}

class VolumeRendererTest : public ::testing::Test {
 protected:
  void SetUp() override {
    CB_REQUIRE_GL();
    std::string err;
    ASSERT_TRUE(renderer.init(&err)) << err;
  }
  VolumeRenderer renderer;
};

TEST_F(VolumeRendererTest, EmptyVolumeShowsOnlyTheBackground) {
  Volume v(glm::ivec3(32));
  renderer.sync(v, Light{});
  RenderOptions opt;
  opt.collect_stats = true;
  ImageRgba8 img = renderImage(renderer, Camera::reference(), opt);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) ASSERT_TRUE(isBackground(img.at(x, y), opt)) << x << "," << y;
  // With skipping, an empty volume costs no samples at all.
  EXPECT_EQ(renderer.lastStats().samples_total, 0u);
}

TEST(OccupiedBoundaryFaces, AFaceForEveryOccupiedCellSideFacingEmptySpace) {
  // One 4-voxel brick occupied (a voxel in its middle, far from the dilation reach of others).
  Volume v = makeSingleVoxel(glm::ivec3(16), {5, 6, 5});
  OccupancyPyramid p = buildOccupancy(v);
  std::vector<glm::vec3> faces = occupiedBoundaryFaces(p, 0);
  EXPECT_EQ(faces.size(), 6u * 6u);  // one cube, 6 faces of 2 triangles
  // Each face lies in a face plane of the brick [4, 8)³ and reaches kBoundaryOverlap of a cell
  // (4 voxels) past its edges.
  const float grown = kBoundaryOverlap * 4.0f;
  for (size_t i = 0; i < faces.size(); i += 6) {
    int in_plane = 0;
    for (int axis = 0; axis < 3; ++axis) {
      bool flat = true;
      for (size_t j = i; j < i + 6; ++j) {
        const float q = faces[j][axis];
        EXPECT_TRUE(q == 4.0f || q == 8.0f || q == 4.0f - grown || q == 8.0f + grown) << q;
        flat = flat && q == faces[i][axis] && (q == 4.0f || q == 8.0f);
      }
      in_plane += flat;
    }
    EXPECT_EQ(in_plane, 1) << "face " << i / 6;
  }
  EXPECT_TRUE(occupiedNear(p, 0, glm::vec3(9.5f)));
  EXPECT_FALSE(occupiedNear(p, 0, glm::vec3(14.5f)));
}

TEST(OccupiedBoundaryFaces, MergedRectanglesHoldEveryBoundaryFaceOnce) {
  // A ball with a cavity and scattered voxels: every unit face between an occupied and an empty
  // (or outside) level-0 cell must lie in exactly one rectangle, and no other face in any.
  Volume v(glm::ivec3(64));
  std::mt19937 rng(test::testSeed("occupancy rectangles", 7));
  std::uniform_int_distribution<int> coord(0, 63);
  for (int z = 0; z < 64; ++z)
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x) {
        const float r = glm::length(glm::vec3(x, y, z) - glm::vec3(30.0f, 34.0f, 28.0f));
        if (r < 20.0f && r > 9.0f) v.set(x, y, z, 0.5f);
      }
  for (int i = 0; i < 40; ++i) v.set(coord(rng), coord(rng), coord(rng), 1.0f);
  OccupancyPyramid p = buildOccupancy(v);
  for (int level = 0; level < 2; ++level) {
    const glm::ivec3 d = p.level_dims[size_t(level)];
    auto occupied = [&](glm::ivec3 c) {
      return glm::all(glm::greaterThanEqual(c, glm::ivec3(0))) && glm::all(glm::lessThan(c, d)) &&
             p.at(level, c) != 0;
    };
    std::map<std::array<int, 5>, int> in_rects;  // axis, side, plane, u, v -> rectangles
    const std::vector<BoundaryRect> rects = occupiedBoundaryRects(p, level);
    for (const BoundaryRect& r : rects)
      for (int b = r.v0; b < r.v1; ++b)
        for (int a = r.u0; a < r.u1; ++a) ++in_rects[{r.axis, r.side, r.plane, a, b}];
    size_t boundary = 0;
    for (int z = 0; z < d.z; ++z)
      for (int y = 0; y < d.y; ++y)
        for (int x = 0; x < d.x; ++x)
          for (int axis = 0; axis < 3; ++axis)
            for (int side = 0; side < 2; ++side) {
              const glm::ivec3 c(x, y, z);
              glm::ivec3 n = c;
              n[axis] += side ? 1 : -1;
              if (!occupied(c) || occupied(n)) continue;
              ++boundary;
              const auto it =
                  in_rects.find({axis, side, c[axis] + side, c[(axis + 1) % 3], c[(axis + 2) % 3]});
              ASSERT_NE(it, in_rects.end()) << "level " << level << " cell " << x << "," << y << ","
                                            << z << " axis " << axis << " side " << side;
              EXPECT_EQ(it->second, 1);
            }
    EXPECT_EQ(in_rects.size(), boundary) << "a rectangle holds a face that is not boundary";
    EXPECT_LT(rects.size() * (level == 0 ? 2 : 1), boundary)
        << "level " << level << ": faces were hardly merged";
  }
}

TEST(OccupiedBoundaryFaces, TrianglesAreWoundOutwardSoFrontFacesAreEntries) {
  // The ray-bounds pass takes entries from front faces and exits from back faces.
  Volume v = makeSingleVoxel(glm::ivec3(16), {5, 6, 5});
  OccupancyPyramid p = buildOccupancy(v);
  std::vector<glm::vec3> faces = occupiedBoundaryFaces(p, 0);
  const glm::vec3 centre(6.0f);  // of the occupied brick [4, 8)³
  ASSERT_EQ(faces.size() % 3, 0u);
  for (size_t i = 0; i < faces.size(); i += 3) {
    glm::vec3 normal = glm::cross(faces[i + 1] - faces[i], faces[i + 2] - faces[i]);
    glm::vec3 outward = (faces[i] + faces[i + 1] + faces[i + 2]) / 3.0f - centre;
    EXPECT_GT(glm::dot(normal, outward), 0.0f) << "triangle " << i / 3;
  }
}

TEST_F(VolumeRendererTest, EveryPlantedVoxelAppearsWithSkipping) {
  Volume v(glm::ivec3(64));
  const glm::ivec3 planted[] = {{0, 0, 0},   {63, 63, 63}, {5, 40, 17}, {31, 32, 33},
                                {50, 3, 60}, {12, 58, 8},  {63, 0, 31}, {20, 20, 50}};
  for (glm::ivec3 p : planted) v.set(p.x, p.y, p.z, 1.0f);
  renderer.sync(v, Light{});
  RenderOptions opt;
  Camera cam = Camera::reference();
  ImageRgba8 img = renderImage(renderer, cam, opt);
  for (glm::ivec3 p : planted) {
    glm::ivec2 px = project(cam, v.voxelToWorld(glm::vec3(p) + 0.5f));
    bool seen = false;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        glm::ivec2 q =
            glm::clamp(px + glm::ivec2(dx, dy), glm::ivec2(0), glm::ivec2(kW - 1, kH - 1));
        seen |= !isBackground(img.at(q.x, q.y), opt);
      }
    EXPECT_TRUE(seen) << "voxel " << p.x << "," << p.y << "," << p.z << " at pixel " << px.x << ","
                      << px.y;
  }
}

TEST_F(VolumeRendererTest, SkippingIsLosslessAndSavesSamples) {
  for (int scene = 0; scene < 2; ++scene) {
    Volume v =
        scene == 0 ? makeSparsePuffs(glm::ivec3(64), 2) : makeBundledCumulus(glm::ivec3(64), 1);
    renderer.sync(v, Light{});
    for (float degrees : {0.0f, 75.0f}) {
      Camera cam = Camera::reference().orbited(degrees);
      RenderOptions opt;
      opt.collect_stats = true;
      ImageRgba8 skip = renderImage(renderer, cam, opt);
      uint64_t skip_samples = renderer.lastStats().samples_total;
      opt.brick_stepping = true;
      ImageRgba8 stepped = renderImage(renderer, cam, opt);
      uint64_t stepped_samples = renderer.lastStats().samples_total;
      opt.brick_stepping = false;
      opt.skip_empty_space = false;
      ImageRgba8 full = renderImage(renderer, cam, opt);
      uint64_t full_samples = renderer.lastStats().samples_total;
      EXPECT_LE(maxChannelDifference(skip, full), 1) << "scene " << scene << " at " << degrees;
      EXPECT_LE(maxChannelDifference(stepped, full), 1) << "scene " << scene << " at " << degrees;
      EXPECT_LT(skip_samples, full_samples);
      EXPECT_LE(stepped_samples, skip_samples);
      if (scene == 0) {
        EXPECT_LT(skip_samples * 3, full_samples) << "sparse scene";
      }
    }
  }
  // An edit that adds cloud where there was none: brick stepping reads the occupancy as it is now
  // (its texture is brought up to date by the next frame that steps, not by sync).
  Volume v = makeSparsePuffs(glm::ivec3(64), 2);
  renderer.sync(v, Light{});
  RenderOptions opt;
  opt.brick_stepping = true;
  const Camera cam = Camera::reference();
  renderImage(renderer, cam, opt);
  const ImageRgba8 before = renderImage(renderer, cam, opt);
  // A 10³ box in a corner with no density and an empty voxel around it.
  auto empty = [&](const VoxelBox& b) {
    for (int z = b.lo.z - 1; z <= b.hi.z; ++z)
      for (int y = b.lo.y - 1; y <= b.hi.y; ++y)
        for (int x = b.lo.x - 1; x <= b.hi.x; ++x)
          if (v.at(x, y, z) != 0.0f) return false;
    return true;
  };
  VoxelBox added;
  for (int corner = 0; corner < 8 && added.empty(); ++corner) {
    const glm::ivec3 lo(corner & 1 ? 50 : 4, corner & 2 ? 50 : 4, corner & 4 ? 50 : 4);
    if (empty({lo, lo + 10})) added = {lo, lo + 10};
  }
  ASSERT_FALSE(added.empty()) << "no empty corner";
  for (int z = added.lo.z; z < added.hi.z; ++z)
    for (int y = added.lo.y; y < added.hi.y; ++y)
      for (int x = added.lo.x; x < added.hi.x; ++x) v.voxelForWrite(x, y, z) = 0.8f;
  v.markDirty(added);
  renderer.sync(v, Light{});
  const ImageRgba8 stepped = renderImage(renderer, cam, opt);
  opt.brick_stepping = false;
  opt.skip_empty_space = false;
  const ImageRgba8 full = renderImage(renderer, cam, opt);
  EXPECT_GT(maxChannelDifference(before, full), 50) << "the added box does not show";
  EXPECT_LE(maxChannelDifference(stepped, full), 1) << "brick stepping after an edit";
}

// With skipping, only the projected rectangle of the ray-bounds boundary is bounded, cast and
// upscaled; the rest of the target is cleared to the background. At full and reduced scale, moving
// or not, with the cloud inside the frame, cut by its edge or out of sight, the frame equals the
// unskipped one (which upscales the whole image).
TEST_F(VolumeRendererTest, SkippingConfinedToTheBoundsRectangleIsLossless) {
  for (int scene = 0; scene < 3; ++scene) {
    // A hard-edged ball too, whose silhouette a rectangle a pixel too small would cut.
    Volume v = scene == 0   ? makeSparsePuffs(glm::ivec3(64), 2)
               : scene == 1 ? makeBundledCumulus(glm::ivec3(64), 1)
                            : makeSphere(glm::ivec3(64), glm::vec3(0.1f, -0.2f, 0.0f), 0.5f);
    renderer.sync(v, Light{});
    Camera near = Camera::reference();
    near.eye = near.target + 0.45f * (near.eye - near.target);  // the cloud cut by the frame
    Camera away = Camera::reference();
    away.target = away.eye + (away.eye - away.target);  // looking away: nothing to cast
    const Camera cameras[] = {Camera::reference(), Camera::reference().orbited(75.0f), near,
                              near.orbited(200.0f), away};
    for (size_t c = 0; c < std::size(cameras); ++c)
      for (float scale : {1.0f, 0.5f, 0.35f}) {
        RenderOptions opt;
        opt.scale = scale;
        opt.moving = scale < 1.0f;
        const ImageRgba8 skip = renderImage(renderer, cameras[c], opt);
        opt.skip_empty_space = false;
        const ImageRgba8 full = renderImage(renderer, cameras[c], opt);
        int cloud = 0;
        for (int y = 0; y < kH; ++y)
          for (int x = 0; x < kW; ++x) cloud += !isBackground(full.at(x, y), opt);
        EXPECT_LE(maxChannelDifference(skip, full), 1)
            << "scene " << scene << " camera " << c << " scale " << scale;
        if (c < 4) {
          EXPECT_GT(cloud, kW * kH / 50) << "scene " << scene << " camera " << c;
        } else {
          EXPECT_EQ(cloud, 0);
        }
      }
  }
}

TEST_F(VolumeRendererTest, SampleStatisticsAddUp) {
  Volume v = makeSphere(glm::ivec3(64), glm::vec3(0.0f), 0.6f);
  renderer.sync(v, Light{});
  RenderOptions opt;
  opt.collect_stats = true;
  for (bool skip : {true, false}) {
    opt.skip_empty_space = skip;
    renderImage(renderer, Camera::reference(), opt);
    RenderStats s = renderer.lastStats();
    ASSERT_TRUE(s.has_samples);
    uint64_t pixels = 0;
    for (uint32_t c : s.histogram) pixels += c;
    EXPECT_EQ(pixels, uint64_t(kW) * kH) << "skip " << skip;  // stencilled pixels count as 0
    EXPECT_NEAR(s.samples_mean, double(s.samples_total) / (kW * kH), 1e-9);
  }
  RenderStats s = renderer.lastStats();
  // No ray can take more samples than the box diagonal in voxels.
  EXPECT_LE(s.samples_max, uint32_t(std::ceil(64 * std::sqrt(3.0))) + 1);
  EXPECT_GT(s.samples_max, 64u);
  EXPECT_NE(s.summary().find("histogram"), std::string::npos);
}

TEST_F(VolumeRendererTest, CameraInsideTheCloudSeesFogEverywhere) {
  Volume v = makeSphere(glm::ivec3(48), glm::vec3(0.0f), 0.9f, 0.3f, 0.1f);
  renderer.sync(v, Light{});
  Camera cam;
  cam.eye = glm::vec3(0.1f, 0.05f, 0.2f);
  cam.target = glm::vec3(-0.5f, 0.0f, -0.6f);
  RenderOptions opt;
  ImageRgba8 img = renderImage(renderer, cam, opt);
  for (int y = 0; y < kH; y += 7)
    for (int x = 0; x < kW; x += 7) ASSERT_FALSE(isBackground(img.at(x, y), opt)) << x << "," << y;
}

TEST_F(VolumeRendererTest, OnlyTheDirtyBoxIsUploadedAndItShows) {
  Volume v(glm::ivec3(64));
  SyncStats first = renderer.sync(v, Light{});
  EXPECT_EQ(first.uploaded, v.bounds());
  SyncStats idle = renderer.sync(v, Light{});
  EXPECT_TRUE(idle.dirty.empty());
  EXPECT_TRUE(idle.uploaded.empty());
  Camera cam = Camera::reference();
  RenderOptions opt;
  ImageRgba8 before = renderImage(renderer, cam, opt);
  // Fill a small block; the light sweeps its shadow downstream, nothing upstream is touched.
  VoxelBox block{{28, 28, 28}, {36, 36, 36}};
  for (int z = 28; z < 36; ++z)
    for (int y = 28; y < 36; ++y)
      for (int x = 28; x < 36; ++x) v.voxelForWrite(x, y, z) = 1.0f;
  v.markDirty(block);
  SyncStats s = renderer.sync(v, Light{});
  EXPECT_EQ(s.dirty, block);
  EXPECT_EQ(s.uploaded.intersect(block), block);
  EXPECT_LT(s.uploaded.voxelCount(), v.bounds().voxelCount());
  ImageRgba8 after = renderImage(renderer, cam, opt);
  glm::ivec2 px = project(cam, glm::vec3(0.0f));
  EXPECT_TRUE(isBackground(before.at(px.x, px.y), opt));
  EXPECT_FALSE(isBackground(after.at(px.x, px.y), opt));
}

TEST_F(VolumeRendererTest, ANewVolumeAtTheSameAddressIsUploadedWhole) {
  // Same object, same generation count, different contents: only the instance id tells.
  Volume v(glm::ivec3(32));
  renderer.sync(v, Light{});
  Volume other(glm::ivec3(32));
  other.voxelForWrite(16, 16, 16) = 1.0f;
  ASSERT_EQ(other.generation(), v.generation());
  v = std::move(other);
  SyncStats s = renderer.sync(v, Light{});
  EXPECT_EQ(s.uploaded, v.bounds());
}

TEST_F(VolumeRendererTest, ReducedScaleRendersAndUpscales) {
  Volume v = makeSphere(glm::ivec3(48), glm::vec3(0.0f), 0.6f);
  renderer.sync(v, Light{});
  Camera cam = Camera::reference();
  RenderOptions opt;
  opt.collect_stats = true;
  ImageRgba8 full = renderImage(renderer, cam, opt);
  opt.scale = 0.5f;
  ImageRgba8 half = renderImage(renderer, cam, opt);
  EXPECT_EQ(renderer.lastStats().width, kW / 2);
  EXPECT_EQ(renderer.lastStats().height, kH / 2);
  // Same picture, softer: the mean difference is small, the centre is cloud in both.
  double sum = 0;
  for (size_t i = 0; i < full.pixels.size(); ++i) sum += std::abs(full.pixels[i] - half.pixels[i]);
  EXPECT_LT(sum / full.pixels.size(), 4.0);
  glm::ivec2 c = project(cam, glm::vec3(0.0f));
  EXPECT_FALSE(isBackground(half.at(c.x, c.y), opt));
}

// A moving frame at half scale marches at twice the step (rayStepVoxels): half the samples, and
// the same cloud — close to the half-scale frame at the resting step, and the frame at rest is
// cast at the resting step again. The bundled cumulus at the painter's grid and default camera.
TEST_F(VolumeRendererTest, AMovingHalfScaleFrameStepsTwiceAsFarAndLooksTheSame) {
  RenderOptions moving;
  moving.scale = 0.5f;
  moving.moving = true;
  EXPECT_EQ(rayStepVoxels(moving), 2.0f);
  EXPECT_EQ(chunkSamples(rayStepVoxels(moving)), 2);
  RenderOptions rest;
  EXPECT_EQ(rayStepVoxels(rest), 1.0f);
  EXPECT_EQ(chunkSamples(1.0f), 4);
  RenderOptions half_rest = moving;
  half_rest.moving = false;
  EXPECT_EQ(rayStepVoxels(half_rest), 1.0f);

  const Volume cumulus = makeBundledCumulus(glm::ivec3(256), 1);
  renderer.sync(cumulus, Light{});
  const Camera cam = Camera::reference();
  moving.collect_stats = half_rest.collect_stats = true;
  const ImageRgba8 coarse = renderImage(renderer, cam, moving);
  const uint64_t coarse_samples = renderer.lastStats().samples_total;
  const ImageRgba8 fine = renderImage(renderer, cam, half_rest);
  const uint64_t fine_samples = renderer.lastStats().samples_total;
  EXPECT_LT(double(coarse_samples), 0.6 * double(fine_samples));
  double sum = 0;
  int worst = 0;
  for (size_t i = 0; i < fine.pixels.size(); ++i) {
    const int d = std::abs(fine.pixels[i] - coarse.pixels[i]);
    sum += d;
    worst = std::max(worst, d);
  }
  const double mean = sum / double(fine.pixels.size());
  std::printf(
      "moving frame: %llu samples against %llu at rest; mean difference %.3f/255, worst %d\n",
      (unsigned long long)coarse_samples, (unsigned long long)fine_samples, mean, worst);
  EXPECT_LT(mean, 0.25);  // measured 0.04
  EXPECT_LE(worst, 4);    // measured 2
}

// Dragging the light ball: while the divisor is 2 a light change is swept coarse into the
// preview texture — the light volume and the pool stay as they were (nothing re-packed) and the
// frame shows the new light, close to the full one; when the divisor returns to 1 the next sync
// sweeps the light volume in full, even though the light did not move again, and the frame shows
// exactly what a plain full sync shows.
TEST_F(VolumeRendererTest, ALightDragIsSweptCoarseAndTheReleaseInFull) {
  Volume v = makeBundledCumulus(glm::ivec3(64), 1);
  Light light;
  renderer.sync(v, light);
  EXPECT_FALSE(renderer.lightIsPreview());
  const std::vector<float> before = renderer.lightVolume().toDense();
  const Camera cam = Camera::reference();
  const ImageRgba8 old_light = renderImage(renderer, cam, RenderOptions{});
  renderer.setLightPreviewDivisor(2);
  light.direction = Light::directionTowards(glm::vec3(-3.0f, 2.0f, 1.0f));
  const SyncStats drag = renderer.sync(v, light);
  EXPECT_TRUE(renderer.lightIsPreview());
  EXPECT_TRUE(drag.light_moved);
  EXPECT_TRUE(drag.light_box.empty()) << "the light volume is not swept while dragging";
  EXPECT_EQ(drag.slots_uploaded, 0) << "nor is the pool re-packed";
  EXPECT_EQ(renderer.lightVolume().toDense(), before);
  EXPECT_GT(renderer.gpuMemory().light_preview, 0u);
  const ImageRgba8 previewed = renderImage(renderer, cam, RenderOptions{});
  EXPECT_EQ(renderer.sync(v, light).slots_uploaded, 0) << "the same drag light: nothing new";
  renderer.setLightPreviewDivisor(1);
  EXPECT_FALSE(renderer.sync(v, light).light_box.empty()) << "the release sweeps in full";
  EXPECT_FALSE(renderer.lightIsPreview());
  LightVolume full;
  sweepLightVolume(full, v, light, v.bounds());
  EXPECT_EQ(renderer.lightVolume().toDense(), full.toDense());
  const ImageRgba8 released = renderImage(renderer, cam, RenderOptions{});
  VolumeRenderer plain;
  std::string err;
  ASSERT_TRUE(plain.init(&err)) << err;
  plain.sync(v, light);
  EXPECT_EQ(maxChannelDifference(released, renderImage(plain, cam, RenderOptions{})), 0);
  // The preview shows the new light: nearer the released frame than the frame before the drag.
  const auto mean = [](const ImageRgba8& a, const ImageRgba8& b) {
    double sum = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i) sum += std::abs(a.pixels[i] - b.pixels[i]);
    return sum / double(a.pixels.size());
  };
  const double to_released = mean(previewed, released), to_old = mean(old_light, released);
  std::printf("preview frame against the released one: mean %.3f/255 (the old light's: %.3f)\n",
              to_released, to_old);
  EXPECT_GT(to_released, 0.0) << "a coarse light is not the full one";
  EXPECT_LT(to_released, 0.25 * to_old);
}

// An animation's frames (LightPreviewOf::kEveryChange): each changed volume is lit by the coarse
// sweep of that volume (the frame a renderer gets from sweeping the same volume coarse), the light
// volume is left as it was meanwhile, and the first sync at divisor 1 sweeps what the frames
// changed: its frame equals a fresh renderer's, bit for bit.
TEST_F(VolumeRendererTest, AnAnimationsFramesAreLitCoarseAndWhatTheyChangedSweptAtTheEnd) {
  Volume v = makeBundledCumulus(glm::ivec3(64), 1);
  const Light light;
  renderer.sync(v, light);
  const std::vector<float> before = renderer.lightVolume().toDense();
  const Camera cam = Camera::reference();
  const RenderOptions opt;
  renderer.setLightPreviewDivisor(2, VolumeRenderer::LightPreviewOf::kEveryChange);
  for (int frame = 0; frame < 3; ++frame) {
    // A slab of cloud moved a little each frame, as the wind's frames do.
    const int at = 12 + 6 * frame;
    const VoxelBox slab{{at, 30, 20}, {at + 8, 38, 44}};
    for (int z = slab.lo.z; z < slab.hi.z; ++z)
      for (int y = slab.lo.y; y < slab.hi.y; ++y)
        for (int x = slab.lo.x; x < slab.hi.x; ++x) v.voxelForWrite(x, y, z) = 0.8f;
    v.markDirty(slab);
    const SyncStats s = renderer.sync(v, light);
    ASSERT_TRUE(renderer.lightIsPreview()) << "frame " << frame;
    EXPECT_TRUE(s.light_box.empty()) << "the light volume is not swept while it plays";
    EXPECT_EQ(renderer.lightVolume().toDense(), before);
    // The light shown is this frame's volume swept coarse: what a renderer shows that starts
    // from another light and previews this one over the same volume.
    VolumeRenderer coarse;
    std::string err;
    ASSERT_TRUE(coarse.init(&err)) << err;
    Light other = light;
    other.direction = Light::directionTowards(glm::vec3(-3.0f, 2.0f, 1.0f));
    coarse.sync(v, other);
    coarse.setLightPreviewDivisor(2);
    coarse.sync(v, light);
    ASSERT_TRUE(coarse.lightIsPreview());
    EXPECT_EQ(maxChannelDifference(renderImage(renderer, cam, opt), renderImage(coarse, cam, opt)),
              0)
        << "frame " << frame;
  }
  renderer.setLightPreviewDivisor(1);
  const SyncStats end = renderer.sync(v, light);
  EXPECT_FALSE(renderer.lightIsPreview());
  EXPECT_FALSE(end.light_box.empty()) << "what the frames changed is swept when they stop";
  LightVolume full;
  sweepLightVolume(full, v, light, v.bounds());
  EXPECT_EQ(renderer.lightVolume().toDense(), full.toDense());
  VolumeRenderer plain;
  std::string err;
  ASSERT_TRUE(plain.init(&err)) << err;
  plain.sync(v, light);
  EXPECT_EQ(maxChannelDifference(renderImage(renderer, cam, opt), renderImage(plain, cam, opt)), 0);
}

// A moved light changes every lit voxel: the sync lists no texel changes (it says the light
// moved, and the changed region is the whole frame), and a frame cast after it — with an edit in
// the same sync, and after the light returns to where it was — equals a fresh renderer's.
// An edit under a light that stayed still lists its texel changes.
TEST_F(VolumeRendererTest, AMovedLightListsNoTexelChangesAndItsFramesAreCastWhole) {
  Volume v = makeBundledCumulus(glm::ivec3(64), 1);
  const Light first;
  renderer.sync(v, first);
  const Camera cam = Camera::reference();
  RenderOptions opt;
  renderImage(renderer, cam, opt);  // a frame held, whose history a partial re-render could use
  const auto edit = [&](int at, float density) {
    const VoxelBox block{glm::ivec3(at), glm::ivec3(at + 6)};
    for (int z = at; z < at + 6; ++z)
      for (int y = at; y < at + 6; ++y)
        for (int x = at; x < at + 6; ++x) v.voxelForWrite(x, y, z) = density;
    v.markDirty(block);
  };
  const auto matchesFreshRenderer = [&](const Light& light) {
    VolumeRenderer plain;
    std::string err;
    if (!plain.init(&err)) return -1;
    plain.sync(v, light);
    return maxChannelDifference(renderImage(renderer, cam, opt), renderImage(plain, cam, opt));
  };
  Light moved = first;
  moved.direction = Light::directionTowards(glm::vec3(-3.0f, 2.0f, 1.0f));
  edit(20, 1.0f);
  const SyncStats s = renderer.sync(v, moved);
  EXPECT_TRUE(s.light_moved);
  EXPECT_TRUE(changedScreenRegion(cam, kW, kH, v, s, opt.style).whole_frame);
  EXPECT_EQ(matchesFreshRenderer(moved), 0);
  const SyncStats back = renderer.sync(v, first);
  EXPECT_TRUE(back.light_moved);
  EXPECT_EQ(matchesFreshRenderer(first), 0);
  // A drag's coarse preview, then its release at the same light, recomputed in full.
  renderer.setLightPreviewDivisor(2);
  EXPECT_TRUE(renderer.sync(v, moved).light_moved);
  ASSERT_TRUE(renderer.lightIsPreview());
  renderImage(renderer, cam, opt);  // a frame of the preview light held
  renderer.setLightPreviewDivisor(1);
  EXPECT_TRUE(renderer.sync(v, moved).light_moved) << "the release recomputed it in full";
  EXPECT_EQ(matchesFreshRenderer(moved), 0);
  renderer.sync(v, first);
  edit(29, 0.0f);  // a hole in the cumulus's core
  const SyncStats still = renderer.sync(v, first);
  EXPECT_FALSE(still.light_moved);
  EXPECT_FALSE(still.changes.empty()) << "an edit under a still light lists its texels";
  EXPECT_FALSE(changedScreenRegion(cam, kW, kH, v, still, opt.style).whole_frame);
  EXPECT_EQ(matchesFreshRenderer(first), 0);
}

}  // namespace
}  // namespace cb
