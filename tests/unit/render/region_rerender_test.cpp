// Pen-up re-rendering of only the changed pixels (changed_region.h, RenderOptions::region): a
// real stroke painted through a PaintSession (hybrid mapping at 128³) next to an earlier one,
// then the rectangle the sync's dirty and light boxes project to re-rendered over the frame
// from before the stroke. It must equal a full re-render within 1/255 per channel at every
// pixel — at the painter's default camera, and with a low sun and a camera from the side, where
// the stroke's shadow on the first stroke's cloud lies outside the stroke's own projection (so the
// light box is what makes it right: without it the test sees stale shadow). At half scale the
// region equals a full half-scale frame inside the rectangle and keeps the old frame outside.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "app/render/changed_region.h"
#include "app/render/image_io.h"
#include "app/render/render_target.h"
#include "app/render/volume_renderer.h"
#include "app/session/paint_session.h"
#include "app/session/synthetic_session.h"
#include "tests/unit/render/gl_test_context.h"

namespace cb {
namespace {

constexpr int kW = 480, kH = 270, kGrid = 128;

// Largest difference of any channel, over pixels where `where(x, y_up)` holds.
template <typename Where>
int worstDifference(const ImageRgba8& a, const ImageRgba8& b, Where where) {
  int worst = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      if (!where(x, a.height - 1 - y)) continue;
      for (int c = 0; c < 4; ++c) worst = std::max(worst, std::abs(a.at(x, y)[c] - b.at(x, y)[c]));
    }
  return worst;
}

bool inside(const ScreenRegion& r, int x, int y_up) {
  return r.whole_frame || (x >= r.rect.x && x < r.rect.x + r.rect.z && y_up >= r.rect.y &&
                           y_up < r.rect.y + r.rect.w);
}

// The first stroke: a long horizontal band on the left half of the screen (the cloud the second
// stroke's shadow falls on in the side view).
SyntheticStroke receiverStroke() {
  SyntheticStroke stroke;
  stroke.control_points = {
      {0.12f * kW, 0.55f * kH}, {0.3f * kW, 0.5f * kH}, {0.46f * kW, 0.55f * kH}};
  stroke.pressure = [](float) { return 0.9f; };
  return stroke;
}

// The second stroke: short, right of the first.
SyntheticStroke shortStroke() {
  SyntheticStroke stroke;
  stroke.control_points = {
      {0.6f * kW, 0.5f * kH}, {0.66f * kW, 0.47f * kH}, {0.72f * kW, 0.5f * kH}};
  stroke.pressure = [](float f) { return 0.6f + 0.3f * f * (1.0f - f); };
  return stroke;
}

// Paints `stroke` into `session` (pen down ... lift) and returns the box it changed.
VoxelBox paint(PaintSession* session, const SyntheticStroke& stroke, int64_t t0_ns) {
  const PenDeviceInfo tablet = syntheticTablet(kW, kH);
  session->setDevice(tablet, t0_ns);
  const uint64_t generation = session->volume().generation();
  const uint32_t mapped = session->strokesMapped();
  for (const PenSample& s : syntheticPenSamples(stroke, tablet, kW, kH, 200.0, t0_ns))
    session->feed(s);
  EXPECT_EQ(session->strokesMapped(), mapped + 1);
  return session->volume().dirtySince(generation);
}

glm::vec3 worldCentre(const Volume& volume, const VoxelBox& box) {
  return volume.voxelToWorld(glm::vec3(box.lo + box.hi) * 0.5f);
}

struct Case {
  const char* name;
  RenderStyle style;
  bool side_view;  // a low sun and a camera from the side (the shadow off the stroke)
};

// The side view: where the second stroke will land (painted once in a scratch session), then a
// low sun behind it as seen from the first, so its shadow falls on the first stroke's cloud, and
// a camera looking across the line between them.
void lookAcrossTheStrokes(const Volume& volume, const VoxelBox& receiver, Camera* camera,
                          Light* light) {
  PaintSession scratch_session({kW, kH, kGrid}, BrushConfig{}, MappingConfig{});
  scratch_session.setQuietMapping(true);
  const glm::vec3 c2 = worldCentre(volume, paint(&scratch_session, shortStroke(), 0));
  const glm::vec3 c1 = worldCentre(volume, receiver);
  glm::vec3 across = c2 - c1;
  across.y = 0.0f;
  light->direction = glm::normalize(glm::normalize(across) + glm::vec3(0.0f, 0.15f, 0.0f));
  camera->target = 0.5f * (c1 + c2);
  camera->eye =
      camera->target +
      3.0f * glm::normalize(glm::cross(glm::normalize(across), glm::vec3(0.0f, 1.0f, 0.0f))) +
      glm::vec3(0.0f, 0.4f, 0.0f);
}

// The pixels the last render cast: the region, grown by a screen-space style's reach (ink: 3),
// clipped; inside it only those whose rays pass through a changed pool slot (a stencil mask; the
// screen-space styles cast the whole rectangle).
void expectCastOnlyTheRegion(const VolumeRenderer& renderer, const ScreenRegion& region,
                             const Case& c) {
  const int reach = screenSpaceReach(c.style);
  const glm::ivec2 lo = glm::max(glm::ivec2(region.rect.x, region.rect.y) - reach, glm::ivec2(0));
  const glm::ivec2 hi =
      glm::min(glm::ivec2(region.rect.x + region.rect.z, region.rect.y + region.rect.w) + reach,
               glm::ivec2(kW, kH));
  const long long rect_pixels = (long long)(hi.x - lo.x) * (hi.y - lo.y);
  std::printf("%s: %lld pixels cast of the region's %lld\n", c.name,
              renderer.lastStats().pixels_cast, rect_pixels);
  EXPECT_GT(renderer.lastStats().pixels_cast, 0);
  if (hasScreenSpacePass(c.style))
    EXPECT_EQ(renderer.lastStats().pixels_cast, rect_pixels);
  else
    EXPECT_LE(renderer.lastStats().pixels_cast, rect_pixels);
}

class RegionRerender : public ::testing::TestWithParam<Case> {};

TEST_P(RegionRerender, EqualsAFullRerenderAfterAStroke) {
  CB_REQUIRE_GL();
  const Case& c = GetParam();
  PaintSession session({kW, kH, kGrid}, BrushConfig{}, MappingConfig{});
  session.setQuietMapping(true);
  std::string error;
  const VoxelBox receiver = paint(&session, receiverStroke(), 1'000'000'000);
  ASSERT_FALSE(receiver.empty());
  Light light;
  Camera camera = session.camera();  // the painter's default view
  if (c.side_view) lookAcrossTheStrokes(session.volume(), receiver, &camera, &light);
  VolumeRenderer renderer;
  ASSERT_TRUE(renderer.init(&error)) << error;
  const Volume& volume = session.volume();
  renderer.sync(volume, light);
  RenderOptions options;
  options.style = c.style;
  RenderTarget full, half, scratch;
  ASSERT_TRUE(full.create(kW, kH, RenderTarget::Format::kRgba8, &error)) << error;
  ASSERT_TRUE(half.create(kW, kH, RenderTarget::Format::kRgba8, &error)) << error;
  ASSERT_TRUE(scratch.create(kW, kH, RenderTarget::Format::kRgba8, &error)) << error;
  renderer.render(camera, kW, kH, full.fbo(), options);
  renderer.render(camera, kW, kH, half.fbo(), options);
  const ImageRgba8 before = full.readRgba8();

  paint(&session, shortStroke(), 5'000'000'000);
  const SyncStats sync = renderer.sync(volume, light);
  ASSERT_FALSE(sync.dirty.empty());
  const ScreenRegion region = changedScreenRegion(camera, kW, kH, volume, sync, c.style);
  const ScreenRegion stroke_only = projectVoxelBoxes(camera, kW, kH, volume, {sync.dirty},
                                                     readReachVoxels(c.style, volume.voxelSize()));
  ASSERT_FALSE(region.empty());
  EXPECT_FALSE(region.whole_frame);
  EXPECT_LT(region.pixels(), (long long)kW * kH) << "the region is the whole frame";

  // The region over the old frame, then the references: full frames with and without skipping.
  options.region = region.renderRegion();
  renderer.render(camera, kW, kH, full.fbo(), options);
  const ImageRgba8 partial = full.readRgba8();
  expectCastOnlyTheRegion(renderer, region, c);
  options.region = glm::ivec4(0);
  renderer.render(camera, kW, kH, scratch.fbo(), options);
  const ImageRgba8 reference = scratch.readRgba8();
  RenderOptions noskip = options;
  noskip.skip_empty_space = false;
  renderer.render(camera, kW, kH, scratch.fbo(), noskip);
  const ImageRgba8 reference_noskip = scratch.readRgba8();

  const auto everywhere = [](int, int) { return true; };
  EXPECT_LE(worstDifference(partial, reference, everywhere), 1);
  EXPECT_LE(worstDifference(partial, reference_noskip, everywhere), 1);
  EXPECT_LE(worstDifference(reference, reference_noskip, everywhere), 1) << "skip is lossless";

  // The stroke is visible, and (side view) its shadow changes pixels outside its projection.
  long changed = 0, changed_off_stroke = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      int e = 0;
      for (int ch = 0; ch < 3; ++ch)
        e = std::max(e, std::abs(before.at(x, y)[ch] - reference.at(x, y)[ch]));
      if (e <= 2) continue;
      ++changed;
      if (!inside(stroke_only, x, kH - 1 - y)) ++changed_off_stroke;
    }
  std::printf(
      "%s: region %dx%d at (%d,%d) = %.1f%% of the frame; %ld pixels changed, %ld outside "
      "the stroke's own projection\n",
      c.name, region.rect.z, region.rect.w, region.rect.x, region.rect.y,
      100.0 * double(region.pixels()) / (kW * kH), changed, changed_off_stroke);
  EXPECT_GT(changed, 200);
  if (c.side_view) {
    EXPECT_GT(changed_off_stroke, 50) << "the shadow should fall outside the stroke's projection";
    // ... so re-rendering only the stroke's projection would leave stale shadow.
    RenderTarget stale;
    ASSERT_TRUE(stale.create(kW, kH, RenderTarget::Format::kRgba8, &error)) << error;
    glBlitNamedFramebuffer(half.fbo(), stale.fbo(), 0, 0, kW, kH, 0, 0, kW, kH, GL_COLOR_BUFFER_BIT,
                           GL_NEAREST);  // the old frame
    RenderOptions stroke_options = options;
    stroke_options.region = stroke_only.renderRegion();
    renderer.render(camera, kW, kH, stale.fbo(), stroke_options);
    EXPECT_GT(worstDifference(stale.readRgba8(), reference, everywhere), 8);
  }

  // Half scale: inside the region as a whole half-scale frame, outside the old frame untouched.
  options.scale = 0.5f;
  options.moving = true;
  options.region = region.renderRegion();
  renderer.render(camera, kW, kH, half.fbo(), options);
  const ImageRgba8 half_partial = half.readRgba8();
  options.region = glm::ivec4(0);
  renderer.render(camera, kW, kH, scratch.fbo(), options);
  const ImageRgba8 half_reference = scratch.readRgba8();
  EXPECT_LE(worstDifference(half_partial, half_reference,
                            [&](int x, int y) { return inside(region, x, y); }),
            1);
  EXPECT_EQ(
      worstDifference(half_partial, before, [&](int x, int y) { return !inside(region, x, y); }),
      0);
  if (const char* keep = std::getenv("CB_KEEP_FRAMES")) {
    const std::string p = std::string(keep) + "/region_" + c.name;
    writePng(p + "_before.png", before);
    writePng(p + "_partial.png", partial);
    writePng(p + "_half_partial.png", half_partial);
  }
}

INSTANTIATE_TEST_SUITE_P(Views, RegionRerender,
                         ::testing::Values(Case{"default_thesis", RenderStyle::kThesis, false},
                                           Case{"side_thesis", RenderStyle::kThesis, true},
                                           Case{"default_ink", RenderStyle::kInk, false}),
                         [](const ::testing::TestParamInfo<Case>& info) {
                           return std::string(info.param.name);
                         });

// The painter's pen-up sequence, three changes in a row at its default camera: after each sync
// the changed region at the moving scale, then at full resolution (the moving frame's rectangle
// with it), except the second change, shown at full resolution at once (so the half-size frame
// colour misses it until the third change's moving frame: the renderer's pending boxes for that
// size must carry it). The full-resolution target equals a fresh full render after every change,
// and the masked casts cover fewer pixels than their rectangles.
TEST(RegionRerenderSequence, MaskedRecastsStayExactAcrossSizes) {
  CB_REQUIRE_GL();
  PaintSession session({kW, kH, kGrid}, BrushConfig{}, MappingConfig{});
  session.setQuietMapping(true);
  std::string error;
  paint(&session, receiverStroke(), 1'000'000'000);
  const Volume& volume = session.volume();
  const Camera camera = session.camera();
  const Light light;
  // The painter's renderer, and another for the references (whole frames only, so the first
  // keeps its frame colours from change to change as in the painter).
  VolumeRenderer renderer, reference_renderer;
  ASSERT_TRUE(renderer.init(&error)) << error;
  ASSERT_TRUE(reference_renderer.init(&error)) << error;
  renderer.sync(volume, light);
  RenderOptions rest;
  RenderOptions moving = rest;
  moving.scale = 0.5f;
  moving.moving = true;
  RenderTarget shown, scratch;
  ASSERT_TRUE(shown.create(kW, kH, RenderTarget::Format::kRgba8, &error)) << error;
  ASSERT_TRUE(scratch.create(kW, kH, RenderTarget::Format::kRgba8, &error)) << error;
  renderer.render(camera, kW, kH, shown.fbo(), moving);  // both sizes hold a whole frame
  renderer.render(camera, kW, kH, shown.fbo(), rest);
  const auto everywhere = [](int, int) { return true; };
  long long masked_pixels = 0, rect_pixels = 0;
  for (int i = 0; i < 3; ++i) {
    SyntheticStroke stroke = i == 1 ? receiverStroke() : shortStroke();
    for (auto& p : stroke.control_points) p.y += (i == 0 ? 0.0f : i == 1 ? -0.25f : 0.3f) * kH;
    paint(&session, stroke, 5'000'000'000LL * (i + 2));
    const SyncStats sync = renderer.sync(volume, light);
    const ScreenRegion region = changedScreenRegion(camera, kW, kH, volume, sync, rest.style);
    ASSERT_FALSE(region.empty());
    reference_renderer.sync(volume, light);
    if (i != 1) {
      // The moving frame: equals a whole moving frame inside the region.
      RenderOptions lit = moving;
      lit.region = region.renderRegion();
      renderer.render(camera, kW, kH, shown.fbo(), lit);
      reference_renderer.render(camera, kW, kH, scratch.fbo(), moving);
      EXPECT_LE(worstDifference(shown.readRgba8(), scratch.readRgba8(),
                                [&](int x, int y) { return inside(region, x, y); }),
                1)
          << "change " << i << ": the half-size frame colour went stale";
    }
    RenderOptions full = rest;
    full.region = region.renderRegion();
    renderer.render(camera, kW, kH, shown.fbo(), full);
    masked_pixels += renderer.lastStats().pixels_cast;
    rect_pixels += region.pixels();
    reference_renderer.render(camera, kW, kH, scratch.fbo(), rest);
    EXPECT_LE(worstDifference(shown.readRgba8(), scratch.readRgba8(), everywhere), 1)
        << "change " << i << ": the masked re-render differs from a full render";
  }
  std::printf("masked casts: %lld pixels against %lld in their rectangles\n", masked_pixels,
              rect_pixels);
  EXPECT_LT(masked_pixels, rect_pixels);
  // A fourth change shown at full resolution only, then a moving frame of a rectangle holding
  // the whole frame: the half-size colour must bring in the second change (outside the third's
  // rectangle, still pending) and the fourth, or it shows them stale.
  SyntheticStroke fourth = shortStroke();
  for (auto& p : fourth.control_points) p.y -= 0.3f * kH;
  paint(&session, fourth, 30'000'000'000LL);
  const SyncStats sync = renderer.sync(volume, light);
  RenderOptions full = rest;
  full.region = changedScreenRegion(camera, kW, kH, volume, sync, rest.style).renderRegion();
  renderer.render(camera, kW, kH, shown.fbo(), full);
  RenderOptions lit = moving;
  lit.region = glm::ivec4(0, 0, kW, kH);
  renderer.render(camera, kW, kH, shown.fbo(), lit);
  EXPECT_LT(renderer.lastStats().pixels_cast, (long long)(kW / 2) * (kH / 2)) << "not masked";
  reference_renderer.sync(volume, light);
  reference_renderer.render(camera, kW, kH, scratch.fbo(), moving);
  EXPECT_LE(worstDifference(shown.readRgba8(), scratch.readRgba8(), everywhere), 1)
      << "the half-size frame colour missed a change shown only at full resolution";
}

// The projection is conservative where it cannot bound the box: the eye inside the (grown) box,
// or a corner behind the near plane, gives the whole frame; an unchanged sync gives nothing.
TEST(ChangedRegion, EyeInsideOrBehindGivesTheWholeFrameAndNothingGivesNothing) {
  const Volume volume(glm::ivec3(64));
  Camera camera = Camera::reference();
  const VoxelBox centre{glm::ivec3(28), glm::ivec3(36)};
  const ScreenRegion r = projectVoxelBoxes(camera, 320, 180, volume, {centre}, 2.0f);
  EXPECT_FALSE(r.empty());
  EXPECT_FALSE(r.whole_frame);
  EXPECT_LT(r.pixels(), 320LL * 180 / 4);
  camera.eye = volume.voxelToWorld(glm::vec3(32.0f));
  camera.target = camera.eye + glm::vec3(0.0f, 0.0f, -1.0f);
  EXPECT_TRUE(projectVoxelBoxes(camera, 320, 180, volume, {centre}, 2.0f).whole_frame);
  // Just outside the grown box's face, nearer than the near plane.
  camera.eye = volume.voxelToWorld(glm::vec3(32.0f, 32.0f, 38.2f));
  EXPECT_TRUE(projectVoxelBoxes(camera, 320, 180, volume, {centre}, 2.0f).whole_frame);
  EXPECT_TRUE(projectVoxelBoxes(camera, 320, 180, volume, {VoxelBox{}}, 2.0f).empty());
  // A box behind the camera only (every corner behind): the whole frame, conservatively.
  camera.eye = volume.voxelToWorld(glm::vec3(32.0f, 32.0f, 60.0f));
  camera.target = camera.eye + glm::vec3(0.0f, 0.0f, 1.0f);
  EXPECT_TRUE(projectVoxelBoxes(camera, 320, 180, volume, {centre}, 2.0f).whole_frame);
}

}  // namespace
}  // namespace cb
