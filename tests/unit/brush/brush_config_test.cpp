// config/brush.toml: the shipped file loads cleanly and equals the built-in defaults; a broken
// file is reported with file and line, and the defaults are kept.
#include <cstdio>
#include <fstream>

#include <gtest/gtest.h>

#include "app/brush/brush_config.h"

namespace cb {
namespace {

std::string writeTemp(const std::string& name, const std::string& text) {
  std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

TEST(BrushConfig, ShippedFileLoadsAndMatchesDefaults) {
  BrushConfig config;
  std::vector<std::string> errors;
  ASSERT_TRUE(loadBrushConfig(std::string(CB_SOURCE_DIR) + "/config/brush.toml", &config, &errors))
      << (errors.empty() ? "" : errors[0]);
  BrushConfig defaults;
  EXPECT_EQ(config.default_brush, defaults.default_brush);
  EXPECT_EQ(config.brush3d.diameter_px, defaults.brush3d.diameter_px);
  EXPECT_EQ(config.brush3d.ink_volume_size, 64);
  EXPECT_EQ(config.skeleton.constraint_iterations, 10);
  EXPECT_EQ(config.skeleton.gravity_px_s2, defaults.skeleton.gravity_px_s2);
  EXPECT_EQ(config.dispersion.fast_speed_px_s, defaults.dispersion.fast_speed_px_s);
  EXPECT_EQ(config.brush2d.bristles, defaults.brush2d.bristles);
}

TEST(BrushConfig, ValuesOverrideDefaults) {
  std::string path = writeTemp("brush_ok.toml",
                               "brush = \"skeleton\"\n[brush2d]\nmax_diameter_px = 20.5\n"
                               "[dispersion]\nmax_dispersion = 0.25\n");
  BrushConfig config;
  std::vector<std::string> errors;
  EXPECT_TRUE(loadBrushConfig(path, &config, &errors));
  EXPECT_EQ(config.default_brush, BrushKind::kSkeleton);
  EXPECT_FLOAT_EQ(config.brush2d.max_diameter_px, 20.5f);
  EXPECT_FLOAT_EQ(config.dispersion.max_dispersion, 0.25f);
}

TEST(BrushConfig, SyntaxErrorNamesFileAndLine) {
  std::string path = writeTemp("brush_syntax.toml", "[brush2d]\nbristles = 12\nsize = = 3\n");
  BrushConfig config;
  std::vector<std::string> errors;
  EXPECT_FALSE(loadBrushConfig(path, &config, &errors));
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_NE(errors[0].find(path + ":3:"), std::string::npos) << errors[0];
  EXPECT_EQ(config.brush2d.bristles, Brush2DParams{}.bristles);  // nothing half-applied
}

TEST(BrushConfig, BadValuesAreReportedAndKeepTheirDefaults) {
  std::string path = writeTemp("brush_values.toml",
                               "brush = \"crayon\"\n[brush3d]\ndiameter_px = -4\n"
                               "ink_volume_size = \"big\"\nslab_thickness = 0.3\n");
  BrushConfig config;
  std::vector<std::string> errors;
  EXPECT_FALSE(loadBrushConfig(path, &config, &errors));
  ASSERT_EQ(errors.size(), 3u);
  EXPECT_NE(errors[0].find(path + ":1:"), std::string::npos) << errors[0];
  EXPECT_NE(errors[1].find(path + ":3:"), std::string::npos) << errors[1];
  EXPECT_NE(errors[1].find("brush3d.diameter_px"), std::string::npos) << errors[1];
  EXPECT_NE(errors[2].find(":4:"), std::string::npos) << errors[2];
  EXPECT_EQ(config.default_brush, BrushConfig{}.default_brush);
  EXPECT_EQ(config.brush3d.diameter_px, Brush3DParams{}.diameter_px);
  EXPECT_EQ(config.brush3d.ink_volume_size, Brush3DParams{}.ink_volume_size);
  EXPECT_FLOAT_EQ(config.brush3d.slab_thickness, 0.3f);  // the good value still applies
}

TEST(BrushConfig, MissingFileIsReported) {
  BrushConfig config;
  std::vector<std::string> errors;
  EXPECT_FALSE(loadBrushConfig("/nonexistent/brush.toml", &config, &errors));
  ASSERT_FALSE(errors.empty());
  EXPECT_NE(errors[0].find("/nonexistent/brush.toml"), std::string::npos);
}

}  // namespace
}  // namespace cb
