// The pen-device corpus (tests/fixtures/hid): every real descriptor parses, and for every
// non-Wacom pen a scripted motion (hover, touch, pressure ramp, tilt sweep, buttons, eraser, out
// of range) decodes field by field. The reports and their expected values come from
// pen_corpus_reports.txt, written by hid-tools' own parser and encoder
// (make_pen_corpus_reports.py), not by the code under test.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "drivers/hid/hid_pen_decoder.h"
#include "drivers/hid/hid_pen_layout.h"
#include "drivers/hid/hid_report_descriptor.h"
#include "tests/unit/drivers/fixtures.h"

namespace cb::hid {
namespace {

struct Range {
  int32_t min = 0, max = 0;
};

struct Step {
  std::string name, expect;
  std::map<std::string, int32_t> values;
  std::vector<uint8_t> report;
  int line = 0;
};

struct Device {
  std::string file;
  uint16_t vendor = 0, product = 0;
  int report_id = 0;
  size_t report_bytes = 0;
  std::map<std::string, Range> ranges;
  std::vector<Step> steps;
};

std::vector<uint8_t> fromHex(const std::string& hex) {
  std::vector<uint8_t> out;
  for (size_t i = 0; i + 1 < hex.size(); i += 2)
    out.push_back(static_cast<uint8_t>(std::stoul(hex.substr(i, 2), nullptr, 16)));
  return out;
}

std::vector<Device> readCorpus() {
  std::ifstream in(std::string(CB_HID_FIXTURE_DIR) + "/pen_corpus_reports.txt");
  std::vector<Device> devices;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    std::istringstream words(line);
    std::string kind;
    words >> kind;
    if (kind == "device") {
      Device d;
      std::string vendor, product;
      words >> d.file >> vendor >> product >> d.report_id >> d.report_bytes;
      d.vendor = static_cast<uint16_t>(std::stoul(vendor, nullptr, 16));
      d.product = static_cast<uint16_t>(std::stoul(product, nullptr, 16));
      for (std::string w; words >> w;) {
        const size_t eq = w.find('='), dots = w.find("..", eq + 2);
        d.ranges[w.substr(0, eq)] = {std::stoi(w.substr(eq + 1, dots - eq - 1)),
                                     std::stoi(w.substr(dots + 2))};
      }
      devices.push_back(d);
    } else if (kind == "step") {
      if (devices.empty()) {
        ADD_FAILURE() << "pen_corpus_reports.txt:" << n << ": step before any device";
        continue;
      }
      Step s;
      s.line = n;
      words >> s.name >> s.expect;
      for (std::string w; words >> w;) {
        if (w == "report") {
          std::string hex;
          words >> hex;
          s.report = fromHex(hex);
          break;
        }
        const size_t eq = w.find('=');
        s.values[w.substr(0, eq)] = std::stoi(w.substr(eq + 1));
      }
      devices.back().steps.push_back(s);
    }
  }
  return devices;
}

bool has(const std::string& expect, const std::string& word) {
  std::istringstream parts(expect);
  for (std::string p; std::getline(parts, p, '+');)
    if (p == word) return true;
  return false;
}

TEST(HidPenCorpus, EveryVendoredDescriptorParses) {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(CB_HID_FIXTURE_DIR)) {
    if (entry.path().extension() != ".rdesc") continue;
    const std::string name = entry.path().filename().string();
    SCOPED_TRACE(name);
    const auto bytes = test::readFixture(name);
    ParseResult r = parseReportDescriptor(bytes.data(), bytes.size());
    ASSERT_TRUE(r.descriptor) << r.error;
    PenLayoutResult l = findPenLayout(*r.descriptor);
    EXPECT_TRUE(l.layout) << l.error;
    ++count;
  }
  EXPECT_GE(count, 20);
}

TEST(HidPenCorpus, ScriptedMotionDecodesFieldByField) {
  const std::vector<Device> devices = readCorpus();
  ASSERT_GE(devices.size(), 15u) << "pen_corpus_reports.txt lists the non-Wacom pens";
  for (const Device& dev : devices) {
    SCOPED_TRACE(dev.file);
    const auto bytes = test::readFixture(dev.file);
    ParseResult parsed = parseReportDescriptor(bytes.data(), bytes.size());
    ASSERT_TRUE(parsed.descriptor) << parsed.error;
    PenLayoutResult found = findPenLayout(*parsed.descriptor);
    ASSERT_TRUE(found.layout) << found.error;
    const PenLayout& l = *found.layout;
    EXPECT_EQ(l.report_id, dev.report_id);
    EXPECT_EQ(l.report_bytes, dev.report_bytes);
    const PenDeviceInfo info = penDeviceInfo(l, dev.vendor, dev.product, dev.file.c_str());
    auto range = [&](const char* k) { return dev.ranges.count(k) ? dev.ranges.at(k) : Range{}; };
    EXPECT_EQ(info.x_max, range("x").max);
    EXPECT_EQ(info.y_max, range("y").max);
    EXPECT_EQ(info.pressure_max, range("tippressure").max);
    EXPECT_EQ(info.tilt_min, range("xtilt").min);
    EXPECT_EQ(info.tilt_max, range("xtilt").max);
    EXPECT_EQ(l.pressure.present, dev.ranges.count("tippressure") == 1);
    EXPECT_EQ(l.eraser.present, dev.ranges.count("eraser") == 1);
    EXPECT_EQ(l.invert.present, dev.ranges.count("invert") == 1);

    HidPenDecoder decoder(l, info, penDriverRulesFor(dev.vendor));
    int64_t t = 0;
    for (const Step& st : dev.steps) {
      SCOPED_TRACE("pen_corpus_reports.txt:" + std::to_string(st.line) + " " + st.name);
      PenSample s;
      DecodeResult r = decoder.decode(st.report.data(), st.report.size(), ++t, s);
      ASSERT_NE(r.status, DecodeStatus::kRejected) << r.reason;
      const bool sample = r.status == DecodeStatus::kSample;
      if (st.expect == "any") continue;
      if (st.expect == "out") {
        EXPECT_TRUE(!sample || !s.in_proximity);
        continue;
      }
      ASSERT_TRUE(sample);
      auto value = [&](const char* k) { return st.values.count(k) ? st.values.at(k) : 0; };
      EXPECT_TRUE(s.in_proximity);
      EXPECT_EQ(s.tool, has(st.expect, "rubber") ? PenTool::kEraser : PenTool::kPen);
      EXPECT_EQ(s.tipDown(), has(st.expect, "touch"));
      EXPECT_EQ((s.buttons & kPenStylus1) != 0, has(st.expect, "barrel"));
      EXPECT_EQ((s.buttons & kPenStylus2) != 0, has(st.expect, "barrel2"));
      EXPECT_EQ(s.x_raw, value("x"));
      EXPECT_EQ(s.y_raw, value("y"));
      EXPECT_EQ(s.pressure_raw, value("tippressure"));
      EXPECT_EQ(s.tilt_x_raw, value("xtilt"));
      EXPECT_EQ(s.tilt_y_raw, value("ytilt"));
    }
  }
}

}  // namespace
}  // namespace cb::hid
