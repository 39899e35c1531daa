// toml_number: integers and numbers from TOML without toml++'s float-to-integer conversion
// (undefined for 1e40 or NaN), every refusal naming FILE:LINE: field: what.
#include "drivers/core/toml_number.h"

#include <gtest/gtest.h>

#include <string>

namespace cb::toml_number {
namespace {

// The value of `key = TEXT` parsed as line 2 of "cfg.toml", or a parse error.
struct Parsed {
  toml::table root;
  std::string error;
};
Parsed parse(const std::string& text) {
  Parsed p;
  try {
    const std::string doc = "[t]\nkey = " + text + "\n";
    p.root = toml::parse(std::string_view(doc), std::string_view("cfg.toml"));
  } catch (const toml::parse_error& e) {
    p.error = std::string(e.description());
  }
  return p;
}

std::string integerRefusal(const std::string& text, int64_t lo, int64_t hi) {
  Parsed p = parse(text);
  if (!p.error.empty()) return "parse: " + p.error;
  std::string why;
  const auto v = integerIn(*p.root["t"]["key"].node(), "", "t.key", lo, hi, &why);
  return v ? "accepted " + std::to_string(*v) : why;
}

TEST(TomlNumber, IntegerRefusesOutOfRangeFloatsNanAndNegatives) {
  EXPECT_EQ(integerRefusal("1e40", 1, 65536), "cfg.toml:2: t.key: outside 1..65536");
  EXPECT_EQ(integerRefusal("-1", 0, 65535), "cfg.toml:2: t.key: -1 is outside 0..65535");
  EXPECT_EQ(integerRefusal("nan", 0, 10), "cfg.toml:2: t.key: expected an integer in 0..10");
  EXPECT_EQ(integerRefusal("inf", 0, 10), "cfg.toml:2: t.key: expected an integer in 0..10");
  EXPECT_EQ(integerRefusal("2.5", 0, 10), "cfg.toml:2: t.key: expected an integer in 0..10");
  EXPECT_EQ(integerRefusal("\"7\"", 0, 10), "cfg.toml:2: t.key: expected an integer in 0..10");
  // 2^63 as a float is past every int64_t; as an integer literal TOML itself refuses it.
  EXPECT_EQ(integerRefusal("9223372036854775808.0", INT64_MIN, INT64_MAX),
            "cfg.toml:2: t.key: outside -9223372036854775808..9223372036854775807");
  EXPECT_EQ(integerRefusal("9223372036854775808", INT64_MIN, INT64_MAX).rfind("parse: ", 0), 0u);
}

TEST(TomlNumber, IntegerAcceptsIntegersAndWholeFloatsInRange) {
  EXPECT_EQ(integerRefusal("1080", 1, 65536), "accepted 1080");
  EXPECT_EQ(integerRefusal("1080.0", 1, 65536), "accepted 1080");
  EXPECT_EQ(integerRefusal("-9223372036854775808", INT64_MIN, INT64_MAX),
            "accepted -9223372036854775808");
}

TEST(TomlNumber, NumberRefusesNanInfinityAndRange) {
  auto refusal = [](const std::string& text) {
    Parsed p = parse(text);
    std::string why;
    const auto v = numberIn(*p.root["t"]["key"].node(), "given.toml", "t.key", 0, 100, &why);
    return v ? "accepted " + std::to_string(*v) : why;
  };
  EXPECT_EQ(refusal("nan").rfind("given.toml:2: t.key: ", 0), 0u) << refusal("nan");
  EXPECT_EQ(refusal("-inf").rfind("given.toml:2: t.key: ", 0), 0u);
  EXPECT_EQ(refusal("1e40").rfind("given.toml:2: t.key: ", 0), 0u);
  EXPECT_EQ(refusal("true"), "given.toml:2: t.key: expected a number");
  EXPECT_EQ(refusal("42"), "accepted 42.000000");
}

}  // namespace
}  // namespace cb::toml_number
