#include "app/mapping/mapping_config.h"

#include <gtest/gtest.h>
#include <fstream>
#include <stdexcept>

namespace cb {
namespace {

std::string writeTemp(const std::string& name, const std::string& text) {
  std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

TEST(MappingConfig, ShippedFileLoadsWithTheThesisParameters) {
  MappingConfig c = loadMappingConfig(std::string(CB_SOURCE_DIR) + "/config/mapping.toml");
  EXPECT_EQ(c.method, MappingMethod::kHybrid);
  EXPECT_EQ(c.circles.initial_diameter_px, 128);
  EXPECT_EQ(c.circles.directions, 16);
  EXPECT_FLOAT_EQ(c.circles.accept_white_ratio, 0.8f);
  EXPECT_FLOAT_EQ(c.circles.drop_empty_ratio, 0.5f);
  EXPECT_FLOAT_EQ(c.circles.white_threshold, 0.5f);
  EXPECT_FLOAT_EQ(c.circles.empty_threshold, 0.05f);
}

TEST(MappingConfig, MissingKeysKeepDefaults) {
  MappingConfig c = loadMappingConfig(writeTemp("partial.toml", "[circles]\ndirections = 8\n"));
  EXPECT_EQ(c.circles.directions, 8);
  EXPECT_EQ(c.circles.initial_diameter_px, MappingConfig{}.circles.initial_diameter_px);
}

TEST(MappingConfig, BadValuesNameTheFileAndKey) {
  try {
    loadMappingConfig(writeTemp("bad_range.toml", "[circles]\naccept_white_ratio = 1.5\n"));
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("accept_white_ratio"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("bad_range.toml"), std::string::npos) << e.what();
  }
  try {
    loadMappingConfig(writeTemp("bad_type.toml", "[edges]\nsamples_per_pixel = \"many\"\n"));
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("edges.samples_per_pixel"), std::string::npos) << e.what();
  }
  EXPECT_THROW(loadMappingConfig(writeTemp("bad_method.toml", "[mapping]\nmethod = \"magic\"\n")),
               std::runtime_error);
  EXPECT_THROW(loadMappingConfig(writeTemp("bad_syntax.toml", "[circles\n")), std::runtime_error);
  EXPECT_THROW(loadMappingConfig("/nonexistent/mapping.toml"), std::runtime_error);
}

// An integer field given 1e40, -1 past an unsigned range, 2^63 or NaN: refused with
// FILE:LINE: field (toml++'s value<int64_t>() would convert the float first, undefined).
TEST(MappingConfig, RefusesNumbersPastTheFieldsType) {
  for (const char* v : {"1e40", "9223372036854775808.0", "nan", "2.5"}) {
    try {
      parseMappingConfigText(std::string("[circles]\ndirections = ") + v + "\n", "m.toml");
      ADD_FAILURE() << v << " accepted";
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(std::string(e.what()).rfind("m.toml:2: circles.directions: ", 0), 0u) << e.what();
    }
  }
}

}  // namespace
}  // namespace cb
