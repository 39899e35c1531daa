#include "app/render/render_config.h"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "app/render/image_io.h"
#include "app/scene/sun_position.h"

namespace cb {
namespace {

std::string writeTemp(const std::string& name, const std::string& text) {
  std::string p = (std::filesystem::temp_directory_path() /
                   ("cb_render_config_" + std::to_string(::getpid()) + "_" + name))
                      .string();
  std::ofstream(p) << text;
  return p;
}

TEST(RenderConfig, ShippedDefaultsLoadAndMatchTheBuiltInOnes) {
  RenderConfig c = loadRenderConfig(std::string(CB_SOURCE_DIR) + "/config/render.toml");
  RenderOptions d;
  EXPECT_EQ(c.options.step_voxels, d.step_voxels);
  EXPECT_EQ(c.options.extinction_per_voxel, d.extinction_per_voxel);
  EXPECT_EQ(c.options.termination_transmittance, d.termination_transmittance);
  EXPECT_EQ(c.options.background, d.background);
  EXPECT_EQ(c.options.style, RenderStyle::kThesis);
  EXPECT_EQ(c.light.direction, Light{}.direction);
  EXPECT_EQ(c.light.extinction, Light{}.extinction);
  EXPECT_FLOAT_EQ(c.moving_scale, RenderConfig{}.moving_scale);
  // The sky stays the flat background by default, and every style parameter in the shipped file
  // is the built-in default (so the styles look as they were tuned).
  EXPECT_EQ(c.options.sky.kind, SkyKind::kNone);
  EXPECT_TRUE(c.warnings.empty()) << c.warnings.front();
  const StyleParams d_params;
  const StyleParams& p = c.options.style_params;
  EXPECT_FLOAT_EQ(p.physical.reflection, d_params.physical.reflection);
  EXPECT_FLOAT_EQ(p.physical.exposure, d_params.physical.exposure);
  EXPECT_EQ(p.physical.octaves, d_params.physical.octaves);
  EXPECT_FLOAT_EQ(p.ink.bleed_sigma, d_params.ink.bleed_sigma);
  EXPECT_EQ(p.cartoon.band_thresholds, d_params.cartoon.band_thresholds);
  EXPECT_FLOAT_EQ(p.sketch.outline_width, d_params.sketch.outline_width);
  EXPECT_EQ(c.options.sky.zenith, SkySettings{}.zenith);
}

// The first warning, or "".
std::string firstWarning(const RenderConfig& c) {
  return c.warnings.empty() ? std::string() : c.warnings.front();
}

TEST(RenderConfig, StyleParametersAreReadAndBadOnesFallBackWithFileLineColumn) {
  RenderConfig c = loadRenderConfig(
      writeTemp("styles.toml",
                "[style.physical]\nforward_g = 0.8\noctaves = 2\n[style.ink]\nbleed_sigma = 2.5\n"
                "sky = true\n[style.cartoon]\nband_thresholds = [0.1, 0.5, 0.9]\n"));
  EXPECT_TRUE(c.warnings.empty()) << firstWarning(c);
  EXPECT_FLOAT_EQ(c.options.style_params.physical.forward_g, 0.8f);
  EXPECT_EQ(c.options.style_params.physical.octaves, 2);
  EXPECT_FLOAT_EQ(c.options.style_params.ink.bleed_sigma, 2.5f);
  EXPECT_TRUE(c.options.style_params.ink.sky);
  EXPECT_EQ(screenSpaceReach(RenderStyle::kInk, c.options.style_params), 6);  // ⌈2.12·2.5⌉
  EXPECT_EQ(c.options.style_params.cartoon.band_thresholds, glm::vec3(0.1f, 0.5f, 0.9f));

  const std::string path =
      writeTemp("bad_styles.toml", "[style.physical]\nreflection = 0.5\n   octaves = 7\n");
  c = loadRenderConfig(path);
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_EQ(c.warnings[0], path +
                               ":3:14: style.physical.octaves must be a whole number in [1, 3]; "
                               "using the default 3");
  EXPECT_FLOAT_EQ(c.options.style_params.physical.reflection, 0.5f);  // the good one is kept
  EXPECT_EQ(c.options.style_params.physical.octaves, 3);

  c = loadRenderConfig(writeTemp("bad_bands.toml",
                                 "[style.cartoon]\nband_thresholds = [0.5, 0.4, 0.9]\n"
                                 "outline = 0.2\n[style.ink]\nwash = \"dark\"\n"));
  ASSERT_EQ(c.warnings.size(), 3u);
  // In the order the tables are read: physical, ink, cartoon, sketch.
  EXPECT_NE(c.warnings[0].find(":5:8: style.ink.wash must be a number in [0, 1]; using the "
                               "default 0.35"),
            std::string::npos)
      << c.warnings[0];
  EXPECT_NE(c.warnings[1].find(":3:11: style.cartoon.outline is not a setting"), std::string::npos)
      << c.warnings[1];
  EXPECT_NE(c.warnings[2].find(":2:19: style.cartoon.band_thresholds must rise"), std::string::npos)
      << c.warnings[2];
  EXPECT_EQ(c.options.style_params.cartoon.band_thresholds, CartoonStyleParams{}.band_thresholds);
}

TEST(RenderConfig, SkyKindsAndTheirErrorsFallBackToNoSky) {
  RenderConfig c = loadRenderConfig(
      writeTemp("sky_lic.toml", "[sky]\nkind = \"lic\"\nlic_seed = 5\nzenith = [0.1, 0.2, 0.3]\n"));
  EXPECT_TRUE(c.warnings.empty()) << firstWarning(c);
  EXPECT_EQ(c.options.sky.kind, SkyKind::kLic);
  EXPECT_EQ(c.options.sky.lic_seed, 5u);
  EXPECT_EQ(c.options.sky.zenith, glm::vec3(0.1f, 0.2f, 0.3f));

  std::string path = writeTemp("sky_bad_kind.toml", "[sky]\nkind = \"clouds\"\n");
  c = loadRenderConfig(path);
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_EQ(c.warnings[0], path +
                               ":2:8: sky.kind must be one of none|colour|lic|image; using "
                               "the default \"none\"");
  EXPECT_EQ(c.options.sky.kind, SkyKind::kNone);

  // A missing picture, a file that is not a PNG: the error names the file and what is wrong.
  path = writeTemp("sky_missing.toml", "[sky]\nkind = \"image\"\nimage = \"no_such_sky.png\"\n");
  c = loadRenderConfig(path);
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_NE(c.warnings[0].find(path + ":3:9: sky.image cannot be used: image file '"),
            std::string::npos)
      << c.warnings[0];
  EXPECT_NE(c.warnings[0].find("no_such_sky.png"), std::string::npos);
  EXPECT_NE(c.warnings[0].find("using the sky kind \"none\""), std::string::npos);
  EXPECT_EQ(c.options.sky.kind, SkyKind::kNone);
  EXPECT_EQ(c.options.sky.image, nullptr);
  const std::string not_png = writeTemp("not_a.png", "plain text, no PNG signature");
  c = loadRenderConfig(
      writeTemp("sky_not_png.toml", "[sky]\nkind = \"image\"\nimage = \"" + not_png + "\"\n"));
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_NE(c.warnings[0].find("cannot read PNG"), std::string::npos) << c.warnings[0];
  c = loadRenderConfig(writeTemp("sky_no_image.toml", "[sky]\nkind = \"image\"\n"));
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_NE(c.warnings[0].find("names no PNG"), std::string::npos) << c.warnings[0];

  // A good picture (relative to the config's folder) loads.
  ImageRgba8 picture;
  picture.width = 20;
  picture.height = 10;
  picture.pixels.assign(20 * 10 * 4, 200);
  const std::string png = writeTemp("sky_picture.png", "");
  writePng(png, picture);
  c = loadRenderConfig(
      writeTemp("sky_image.toml", "[sky]\nkind = \"image\"\nimage = \"" +
                                      std::filesystem::path(png).filename().string() + "\"\n"));
  EXPECT_TRUE(c.warnings.empty()) << firstWarning(c);
  ASSERT_NE(c.options.sky.image, nullptr);
  EXPECT_EQ(c.options.sky.image->width, 20);
  // Sizes are checked from the header, before the pixels are allocated.
  try {
    readPng(png, 100);
    ADD_FAILURE() << "a 200-pixel PNG passed a 100-pixel limit";
  } catch (const ImageIoError& e) {
    EXPECT_NE(std::string(e.what()).find("20x10, more than the 100 pixels"), std::string::npos)
        << e.what();
  }
}

TEST(RenderConfig, TimeOfDaySetsTheSunAndWinsOverDirection) {
  const std::string path =
      writeTemp("evening.toml", "[light]\ndirection = [1, 1, 1]\ntime_of_day = \"18:00\"\n");
  RenderConfig c = loadRenderConfig(path);
  const SunPosition sun = sunPosition(18.0f, kDefaultLatitudeDeg, kDefaultDayOfYear);
  EXPECT_NEAR(glm::length(c.light.direction - sun.direction), 0.0f, 1e-5f);
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_NE(c.warnings[0].find(path + ":3:15: light.time_of_day 18:00"), std::string::npos)
      << c.warnings[0];
  EXPECT_NE(c.warnings[0].find("wins over light.direction"), std::string::npos);
  // Warmer and dimmer than the configured (noon) colour.
  EXPECT_LT(c.light.colour.b / c.light.colour.r, Light{}.colour.b / Light{}.colour.r);
  EXPECT_LT(c.light.colour.g, Light{}.colour.g);

  c = loadRenderConfig(writeTemp("noon.toml",
                                 "[light]\ntime_of_day = \"12:00\"\nlatitude = 0\n"
                                 "day_of_year = 80\n"));
  EXPECT_GT(c.light.direction.y, 0.99f);  // equinox noon on the equator: overhead

  c = loadRenderConfig(writeTemp("night.toml", "[light]\ntime_of_day = \"23:00\"\n"));
  EXPECT_NEAR(std::asin(c.light.direction.y) * 57.29578f, 1.0f, 0.01f);
  EXPECT_NE(firstWarning(c).find("below the horizon"), std::string::npos) << firstWarning(c);

  c = loadRenderConfig(
      writeTemp("bad_time.toml", "[light]\ndirection = [1, 1, 1]\ntime_of_day = \"25:00\"\n"));
  EXPECT_EQ(c.light.direction, glm::normalize(glm::vec3(1.0f)));
  EXPECT_NE(firstWarning(c).find(":3:15: light.time_of_day must be \"HH:MM\""), std::string::npos)
      << firstWarning(c);
}

TEST(RenderConfig, ValuesAreReadAndBadOnesNamed) {
  RenderConfig c = loadRenderConfig(
      writeTemp("ok.toml", "[raycast]\nstep_voxels = 0.5\n[background]\ncolour = [0,0,0,0]\n"));
  EXPECT_EQ(c.options.step_voxels, 0.5f);
  EXPECT_EQ(c.options.background, glm::vec4(0.0f));
  auto message = [](const std::string& text) {
    try {
      loadRenderConfig(writeTemp("bad.toml", text));
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message("[raycast]\nstep_voxels = 0\n").find("raycast.step_voxels"), std::string::npos);
  EXPECT_NE(message("[raycast]\nstep_voxels = \"x\"\n")
                .find("bad.toml:2: raycast.step_voxels: expected a number"),
            std::string::npos);
  EXPECT_NE(message("[light]\ncolour = [1, 2]\n").find("light.colour"), std::string::npos);
  EXPECT_NE(message("[raycast\n").find("bad.toml:"), std::string::npos);
  EXPECT_NE(message("[style]\nname = \"watercolour\"\n").find("style.name"), std::string::npos);
  EXPECT_EQ(loadRenderConfig(writeTemp("ink.toml", "[style]\nname = \"ink\"\n")).options.style,
            RenderStyle::kInk);
}

// The render settings a journal records (formatRenderConfig) read back to the same settings,
// sky and style parameters included, so a replay renders what the participant saw.
TEST(RenderConfig, FormattedSettingsReadBackTheSame) {
  const std::string path = writeTemp("format.toml", R"([style]
name = "ink"
[light]
time_of_day = "17:30"
[sky]
kind = "lic"
zenith = [0.1, 0.2, 0.9]
lic_seed = 2147483000
lic_coverage = 0.7
[style.physical]
octaves = 2
erosion = 0.3
[style.ink]
wash = 0.5
bleed_sigma = 2.0
sky = true
[style.cartoon]
band_thresholds = [0.1, 0.5, 0.9]
[style.sketch]
outline_width = 0.4
)");
  const RenderConfig a = loadRenderConfig(path);
  const RenderConfig b = parseRenderConfigText(formatRenderConfig(a), "journal");
  EXPECT_TRUE(b.warnings.empty()) << b.warnings.front();
  EXPECT_EQ(b.options.style, RenderStyle::kInk);
  EXPECT_EQ(b.light.direction, a.light.direction);  // the 17:30 sun, as a direction
  EXPECT_EQ(b.light.colour, a.light.colour);
  EXPECT_EQ(b.options.sky.kind, SkyKind::kLic);
  EXPECT_EQ(b.options.sky.zenith, a.options.sky.zenith);
  EXPECT_EQ(b.options.sky.lic_seed, 2147483000u);
  EXPECT_EQ(b.options.sky.lic_coverage, a.options.sky.lic_coverage);
  const StyleParams &p = a.options.style_params, &q = b.options.style_params;
  EXPECT_EQ(q.physical.octaves, 2);
  EXPECT_EQ(q.physical.erosion, p.physical.erosion);
  EXPECT_EQ(q.ink.wash, p.ink.wash);
  EXPECT_EQ(q.ink.bleed_sigma, p.ink.bleed_sigma);
  EXPECT_TRUE(q.ink.sky);
  EXPECT_EQ(q.cartoon.band_thresholds, p.cartoon.band_thresholds);
  EXPECT_EQ(q.sketch.outline_width, p.sketch.outline_width);
  EXPECT_EQ(formatRenderConfig(b), formatRenderConfig(a));
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace cb
