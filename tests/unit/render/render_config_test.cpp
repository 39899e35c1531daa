#include "app/render/render_config.h"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

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
  EXPECT_NE(message("[raycast]\nstep_voxels = \"x\"\n").find("must be a number"),
            std::string::npos);
  EXPECT_NE(message("[light]\ncolour = [1, 2]\n").find("light.colour"), std::string::npos);
  EXPECT_NE(message("[raycast\n").find("bad.toml:"), std::string::npos);
  EXPECT_NE(message("[style]\nname = \"watercolour\"\n").find("style.name"), std::string::npos);
  EXPECT_EQ(loadRenderConfig(writeTemp("ink.toml", "[style]\nname = \"ink\"\n")).options.style,
            RenderStyle::kInk);
}

}  // namespace
}  // namespace cb
