// Every quoted #include in app/, drivers/ and calibration/ against the layering the READMEs
// state (layering_rules.h): an include no README allows fails with FILE:LINE and the rule.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "tests/layering/layering_rules.h"
#include "tests/support/file_text.h"

namespace cb::layering {
namespace {

namespace fs = std::filesystem;
using Rules = std::map<std::string, std::vector<std::string>>;

const std::string kRoot = CB_SOURCE_DIR;

Rules projectRules() {
  Rules rules = appTable(test::readText(kRoot + "/app/README.md"));
  for (const auto& entry : fs::directory_iterator(kRoot + "/drivers")) {
    if (!entry.is_directory()) continue;
    const std::string readme = test::readText(entry.path().string() + "/README.md");
    rules["drivers/" + entry.path().filename().string()] =
        allowedPrefixes(mayIncludeParagraph(readme));
  }
  rules["calibration"] =
      allowedPrefixes(mayIncludeParagraph(test::readText(kRoot + "/calibration/README.md")));
  return rules;
}

std::string describe(const std::vector<std::string>& prefixes) {
  std::string text;
  for (const std::string& prefix : prefixes) text += (text.empty() ? "" : ", ") + prefix;
  return text.empty() ? "(nothing outside itself)" : text;
}

TEST(LayeringTest, ReadmeTablesAreRead) {
  const Rules rules = projectRules();
  // Every app folder with sources has a row, and the rows name what they allow: a README whose
  // table lost its backticks would otherwise allow nothing and fail below for the wrong reason.
  for (const auto& entry : fs::directory_iterator(kRoot + "/app")) {
    if (!entry.is_directory()) continue;
    const std::string room = "app/" + entry.path().filename().string();
    EXPECT_TRUE(rules.count(room)) << "app/README.md has no row for " << room;
  }
  ASSERT_TRUE(rules.count("app/render"));
  EXPECT_FALSE(rules.at("app/render").empty());
  ASSERT_TRUE(rules.count("drivers/hid"));
  EXPECT_FALSE(rules.at("drivers/hid").empty());
}

TEST(LayeringTest, NoIncludeOutsideTheStatedLayering) {
  const Rules rules = projectRules();
  int checked = 0;
  for (const char* top : {"app", "drivers", "calibration"}) {
    for (const auto& entry : fs::recursive_directory_iterator(kRoot + "/" + top)) {
      const std::string ext = entry.path().extension().string();
      if (!entry.is_regular_file() || (ext != ".h" && ext != ".cpp")) continue;
      const std::string file = fs::relative(entry.path(), kRoot).string();
      for (const Include& include : projectIncludes(file, test::readText(entry.path()))) {
        ++checked;
        const auto rule = rules.find(roomOf(file));
        EXPECT_TRUE(allowed(include, rules))
            << include.file << ":" << include.line << ": includes " << include.target
            << "; the README allows " << roomOf(file) << " only "
            << (rule == rules.end() ? "(no rule)" : describe(rule->second));
      }
    }
  }
  // The walk found the tree (a wrong CB_SOURCE_DIR would check nothing and pass).
  EXPECT_GT(checked, 500);
}

// The checker itself refuses what it should, on made-up text.
TEST(LayeringTest, CheckerRefusesUpwardAndUnlistedIncludes) {
  const Rules rules = appTable(
      "| render/ | ray caster | `scene`, `core`, `drivers/core/toml_number.h`; never shell |\n"
      "| cli/ | commands | `app`, `drivers` |\n");
  ASSERT_EQ(rules.size(), 2u);
  EXPECT_TRUE(allowed({"app/render/a.cpp", 1, "app/scene/camera.h"}, rules));
  EXPECT_TRUE(allowed({"app/render/gl/d.cpp", 1, "app/render/volume_renderer.h"}, rules));
  EXPECT_TRUE(allowed({"app/render/a.cpp", 1, "drivers/core/toml_number.h"}, rules));
  EXPECT_FALSE(allowed({"app/render/a.cpp", 1, "drivers/core/clock.h"}, rules));
  EXPECT_FALSE(allowed({"app/render/a.h", 1, "app/shell/painter/hud_items.h"}, rules));
  EXPECT_FALSE(allowed({"app/render/a.h", 1, "app/scenery/x.h"}, rules));
  EXPECT_TRUE(allowed({"app/cli/c.cpp", 1, "drivers/evdev/evdev_pen_source.h"}, rules));
  EXPECT_TRUE(allowed({"app/main.cpp", 1, "app/cli/commands.h"}, rules));
  EXPECT_FALSE(allowed({"app/study/s.cpp", 1, "app/shell/screen.h"}, rules));  // no row
  EXPECT_EQ(mayIncludeParagraph("x\n\nMay include: `drivers/core`. Nothing from `app/`.\n"),
            "May include: `drivers/core`. ");
  const std::vector<Include> found =
      projectIncludes("app/x.cpp", "#include <vector>\n  # include \"app/core/a.h\"\n");
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].line, 2);
  EXPECT_EQ(found[0].target, "app/core/a.h");
}

}  // namespace
}  // namespace cb::layering
