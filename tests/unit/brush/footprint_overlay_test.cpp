// The live footprint overlay on EGL surfaceless (llvmpipe): a changed rectangle uploads alone and
// shows in the next frame over the cached scene; the cursor ring is drawn where the pen is.
#include "app/render/footprint_overlay.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "app/brush/stroke_engine.h"
#include "app/render/render_target.h"
#include "tests/unit/render/gl_test_context.h"

namespace cb {
namespace {

constexpr int kW = 160, kH = 100;

// A cached "scene": a target cleared to a known colour.
void fillScene(RenderTarget* scene) {
  glBindFramebuffer(GL_FRAMEBUFFER, scene->fbo());
  glViewport(0, 0, kW, kH);
  glClearColor(0.2f, 0.4f, 0.6f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
}

TEST(FootprintOverlay, ShowsExactlyTheUploadedFootprintOverTheScene) {
  CB_REQUIRE_GL();
  std::string err;
  RenderTarget scene, frame;
  ASSERT_TRUE(scene.create(kW, kH, RenderTarget::Format::kRgba8, &err)) << err;
  ASSERT_TRUE(frame.create(kW, kH, RenderTarget::Format::kRgba8, &err)) << err;
  fillScene(&scene);
  FootprintOverlay overlay;
  ASSERT_TRUE(overlay.init(&err)) << err;
  overlay.beginFootprint(kW, kH);

  Footprint fp(kW, kH);
  for (int y = 20; y < 30; ++y)
    for (int x = 100; x < 120; ++x) fp.at(x, y) = 1.0f;
  fp.at(5, 90) = 1.0f;  // outside the uploaded rectangle: must not show yet
  EXPECT_EQ(overlay.upload(fp, {100, 20, 120, 30}), 200u);
  OverlayStyle style;
  style.ink_opacity = 1.0f;
  OverlayCursor cursor;
  cursor.visible = false;
  overlay.draw(scene.texture(), frame.fbo(), kW, kH, cursor, style);
  ImageRgba8 img = frame.readRgba8();  // row 0 at the top, like the footprint
  EXPECT_EQ(img.at(110, 25)[0], 255);  // ink (white) where the footprint is 1
  EXPECT_EQ(img.at(110, 25)[2], 255);
  EXPECT_NEAR(img.at(60, 60)[0], 51, 1);  // the scene elsewhere
  EXPECT_NEAR(img.at(60, 60)[2], 153, 1);
  EXPECT_NEAR(img.at(5, 90)[0], 51, 1);  // not uploaded yet

  EXPECT_EQ(overlay.upload(fp, {5, 90, 6, 91}), 1u);
  overlay.draw(scene.texture(), frame.fbo(), kW, kH, cursor, style);
  img = frame.readRgba8();
  EXPECT_EQ(img.at(5, 90)[0], 255);
}

TEST(FootprintOverlay, DrawsTheCursorRingAtThePen) {
  CB_REQUIRE_GL();
  std::string err;
  RenderTarget scene, frame;
  ASSERT_TRUE(scene.create(kW, kH, RenderTarget::Format::kRgba8, &err)) << err;
  ASSERT_TRUE(frame.create(kW, kH, RenderTarget::Format::kRgba8, &err)) << err;
  fillScene(&scene);
  FootprintOverlay overlay;
  ASSERT_TRUE(overlay.init(&err)) << err;
  overlay.beginFootprint(kW, kH);
  OverlayCursor cursor;
  cursor.screen_px = {40.0f, 30.0f};
  cursor.radius_px = 10.0f;
  OverlayStyle style;
  style.cursor_colour = {1.0f, 0.0f, 0.0f, 1.0f};
  style.cursor_width_px = 2.0f;
  overlay.draw(scene.texture(), frame.fbo(), kW, kH, cursor, style);
  ImageRgba8 img = frame.readRgba8();
  // Pixel centres sit at +0.5, so ring pixels are within half a pixel of the ring: ≥ 90 % red.
  EXPECT_GE(img.at(50, 30)[0], 230);  // on the ring, right of the centre (x + r)
  EXPECT_LE(img.at(50, 30)[1], 20);
  EXPECT_GE(img.at(39, 20)[0], 230);  // above the centre (y − r, y down)
  EXPECT_LE(img.at(39, 20)[1], 20);
  EXPECT_LE(img.at(39, 40)[1], 20);       // below the centre
  EXPECT_NEAR(img.at(40, 30)[0], 51, 1);  // the centre stays clear
}

TEST(FootprintOverlay, BrushRectanglesKeepTheTextureEqualToTheFootprint) {
  CB_REQUIRE_GL();
  std::string err;
  FootprintOverlay overlay;
  ASSERT_TRUE(overlay.init(&err)) << err;
  BrushConfig config;
  config.default_brush = BrushKind::k3D;
  StrokeEngine engine(config, kW, kH);
  overlay.beginFootprint(kW, kH);
  size_t uploaded = 0;
  for (int i = 0; i < 60; ++i) {
    BrushInput in{{20.0f + 2.0f * i, 50.0f + 10.0f * std::sin(i * 0.2f)},
                  0.3f + 0.01f * i,
                  float(i - 30),
                  0.0f,
                  int64_t(i) * 5000000};
    uploaded +=
        overlay.upload(engine.footprint(), i == 0 ? engine.beginStroke(in) : engine.addSample(in));
  }
  RenderTarget scene, frame;
  ASSERT_TRUE(scene.create(kW, kH, RenderTarget::Format::kRgba8, &err)) << err;
  ASSERT_TRUE(frame.create(kW, kH, RenderTarget::Format::kRgba8, &err)) << err;
  fillScene(&scene);
  OverlayStyle style;
  style.ink_opacity = 1.0f;
  style.ink_colour = {1.0f, 1.0f, 1.0f};
  OverlayCursor cursor;
  cursor.visible = false;
  overlay.draw(scene.texture(), frame.fbo(), kW, kH, cursor, style);
  ImageRgba8 img = frame.readRgba8();
  const Footprint& fp = engine.footprint();
  int worst = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      int expected = int(std::lround((0.2f + (1.0f - 0.2f) * fp.at(x, y)) * 255.0f));
      worst = std::max(worst, std::abs(img.at(x, y)[0] - expected));
    }
  EXPECT_LE(worst, 2);
  EXPECT_LT(uploaded, size_t(kW) * kH * 60 / 4);  // rectangles, not whole footprints
}

}  // namespace
}  // namespace cb

namespace cb {
namespace {

TEST(FootprintOverlay, IncrementalFramesEqualAFullComposite) {
  CB_REQUIRE_GL();
  std::string err;
  RenderTarget scene, frame;
  ASSERT_TRUE(scene.create(kW, kH, RenderTarget::Format::kRgba8, &err)) << err;
  ASSERT_TRUE(frame.create(kW, kH, RenderTarget::Format::kRgba8, &err)) << err;
  fillScene(&scene);
  FootprintOverlay overlay;
  ASSERT_TRUE(overlay.init(&err)) << err;
  BrushConfig config;
  config.default_brush = BrushKind::k2D;
  StrokeEngine engine(config, kW, kH);
  OverlayCursor cursor;
  cursor.radius_px = 6.0f;
  size_t composited = 0;
  for (int stroke = 0; stroke < 2; ++stroke) {
    for (int i = 0; i < 40; ++i) {
      BrushInput in{
          {20.0f + 3.0f * i, 30.0f + 40.0f * stroke}, 0.6f, 0.0f, 0.0f, int64_t(i) * 5000000};
      FootprintRect r = i == 0 ? engine.beginStroke(in) : engine.addSample(in);
      if (i == 0) overlay.beginFootprint(kW, kH);
      overlay.upload(engine.footprint(), r);
      cursor.screen_px = in.footprint_px;
      overlay.draw(scene.texture(), frame.fbo(), kW, kH, cursor);
      if (stroke == 1 && i > 0) composited += overlay.lastCompositedPixels();
    }
    engine.finishStroke();  // tip-up
  }
  ImageRgba8 incremental = frame.readRgba8();
  overlay.invalidate();
  overlay.draw(scene.texture(), frame.fbo(), kW, kH, cursor);
  EXPECT_EQ(overlay.lastCompositedPixels(), size_t(kW) * kH);
  ImageRgba8 full = frame.readRgba8();
  EXPECT_EQ(incremental.pixels, full.pixels);
  // The first stroke's ink was erased at the second tip-down: only the second row is inked.
  EXPECT_NEAR(full.at(60, 30)[0], 51, 1);
  EXPECT_GT(full.at(60, 70)[0], 100);
  EXPECT_LT(composited, size_t(kW) * kH * 39 / 4);  // far less than full frames
}

// With no ink on the footprint a whole frame is the scene copied, opaque, with the cursor
// composited over it alone; the pixels are the shader's over every pixel (bit-identical: the
// shader reads the same texel at each pixel's centre and mixes in nothing), and once ink is
// uploaded every pixel goes through the shader again.
TEST(FootprintOverlay, AFrameWithoutInkIsTheSceneCopiedWithTheCursor) {
  CB_REQUIRE_GL();
  std::string err;
  RenderTarget scene, frame, reference;
  ASSERT_TRUE(scene.create(kW, kH, RenderTarget::Format::kRgba8, &err)) << err;
  ASSERT_TRUE(frame.create(kW, kH, RenderTarget::Format::kRgba8, &err)) << err;
  ASSERT_TRUE(reference.create(kW, kH, RenderTarget::Format::kRgba8, &err)) << err;
  // A scene that varies per pixel, with α below 1 (the frame shows it opaque).
  std::vector<uint8_t> texels(size_t(kW) * kH * 4);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      uint8_t* t = &texels[(size_t(y) * kW + x) * 4];
      t[0] = uint8_t(x * 37 + y), t[1] = uint8_t(y * 11 + x * 3), t[2] = uint8_t(x ^ y), t[3] = 90;
    }
  glTextureSubImage2D(scene.texture(), 0, 0, 0, kW, kH, GL_RGBA, GL_UNSIGNED_BYTE, texels.data());
  OverlayCursor cursor;
  cursor.screen_px = {40.0f, 30.0f};
  cursor.radius_px = 10.0f;
  OverlayStyle style;
  style.cursor_colour = {1.0f, 0.0f, 0.0f, 1.0f};
  style.cursor_width_px = 2.0f;
  FootprintOverlay copied, shaded;
  ASSERT_TRUE(copied.init(&err)) << err;
  ASSERT_TRUE(shaded.init(&err)) << err;
  copied.beginFootprint(kW, kH);
  shaded.beginFootprint(kW, kH);
  // The shader's whole pass: ink of 0 uploaded over the whole footprint counts as ink.
  Footprint none(kW, kH);
  EXPECT_EQ(shaded.upload(none, {0, 0, kW, kH}), size_t(kW) * kH);
  copied.draw(scene.texture(), frame.fbo(), kW, kH, cursor, style);
  shaded.draw(scene.texture(), reference.fbo(), kW, kH, cursor, style);
  EXPECT_LT(copied.lastCompositedPixels(), size_t(kW) * kH / 4) << "only the cursor shaded";
  EXPECT_EQ(shaded.lastCompositedPixels(), size_t(kW) * kH);
  const ImageRgba8 a = frame.readRgba8(), b = reference.readRgba8();
  size_t differ = 0, translucent = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      for (int c = 0; c < 4; ++c) differ += a.at(x, y)[c] != b.at(x, y)[c];
      translucent += a.at(x, y)[3] != 255;
    }
  EXPECT_EQ(differ, 0u);
  EXPECT_EQ(translucent, 0u);
  EXPECT_GE(a.at(50, 30)[0], 230) << "the cursor ring";
  // Ink: the next whole frame is shaded everywhere.
  Footprint fp(kW, kH);
  fp.at(5, 5) = 1.0f;
  EXPECT_EQ(copied.upload(fp, {5, 5, 6, 6}), 1u);
  copied.invalidate();
  copied.draw(scene.texture(), frame.fbo(), kW, kH, cursor, style);
  EXPECT_EQ(copied.lastCompositedPixels(), size_t(kW) * kH);
}

}  // namespace
}  // namespace cb
