// Every config reader takes its numbers through toml_number: a number no setting can hold
// (1e40, -1 where the setting is positive, 2^63 written as a float, NaN) is refused before any
// conversion, and the refusal names FILE:LINE: field. One row per reader; each file puts the
// value on line 2. (mapping.toml: mapping_config_test; its ranges are checked after reading.)
#include <fstream>
#include <functional>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "app/brush/brush_config.h"
#include "app/kiosk/kiosk_config.h"
#include "app/render/render_config.h"
#include "calibration/calibration_profile.h"
#include "calibration/n_point_calibration.h"
#include "calibration/pressure_range.h"

namespace cb {
namespace {

// The refusal for the file `text` read as `name`, or "" when the reader accepted it.
using Reader = std::function<std::string(const std::string& text, const std::string& name)>;

std::string thrown(const std::function<void()>& read) {
  try {
    read();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

struct ReaderCase {
  const char* file;      // the name the reader is given
  const char* before;    // line 1: the table header
  const char* field;     // line 2 sets this field (table.key)
  const char* after;     // the rest of the file
  const char* ordinary;  // a value the reader takes (null: the file needs more, tested elsewhere)
  Reader read;
};

const ReaderCase kReaders[] = {
    {"brush.toml", "[brush2d]\n", "brush2d.max_diameter_px", "", "30",
     [](const std::string& text, const std::string& name) {
       BrushConfig config;
       std::vector<std::string> errors;
       parseBrushConfigText(text, name, &config, &errors);
       return errors.empty() ? std::string() : errors[0];
     }},
    {"render.toml", "[raycast]\n", "raycast.step_voxels", "", "1",
     [](const std::string& text, const std::string& name) {
       return thrown([&] { parseRenderConfigText(text, name); });
     }},
    {"render.toml", "[light]\n", "light.extinction", "", "0.5",
     [](const std::string& text, const std::string& name) {
       return thrown([&] { parseRenderConfigText(text, name); });
     }},
    {"kiosk.toml", "[visitor]\n", "visitor.idle_seconds", "", "60",
     [](const std::string& text, const std::string& name) {
       const std::string path = ::testing::TempDir() + name;
       std::ofstream(path) << text;
       std::string why = thrown([&] { loadKioskConfig(path); });
       // The reader names the path it opened; the table compares the file name.
       if (why.rfind(::testing::TempDir(), 0) == 0) why.erase(0, ::testing::TempDir().size());
       return why;
     }},
    {"calibration.toml", "[pressure]\n", "pressure.contact_down", "", "0.05",
     [](const std::string& text, const std::string& name) {
       const ProfileParseResult r = parseCalibrationProfile(text, name);
       return r.errors.empty() ? std::string() : r.errors[0];
     }},
    {"pressure_range.toml", "[pressure_range]\n", "pressure_range.lo", "hi = 1.0\n", "0.25",
     [](const std::string& text, const std::string& name) {
       std::string error;
       return pressureRangeFromToml(text, &error, name) ? std::string() : error;
     }},
    {"taps.toml", "[screen]\n", "screen.width", "height = 1080\n", nullptr,
     [](const std::string& text, const std::string& name) {
       std::string error;
       return parseTapFile(text, name, &error) ? std::string() : error;
     }},
};

// 2^63 does not fit int64_t (a TOML integer literal that large is a parse error), so it comes
// as a float.
const char* const kUnholdable[] = {"1e40", "-1", "9.223372036854775808e18", "nan"};

TEST(TomlNumberReaders, EveryReaderRefusesUnholdableNumbersNamingFileLineField) {
  for (const ReaderCase& r : kReaders) {
    const std::string key = std::string(r.field).substr(std::string(r.field).find('.') + 1);
    for (const char* value : kUnholdable) {
      SCOPED_TRACE(std::string(r.field) + " = " + value);
      const std::string text = std::string(r.before) + key + " = " + value + "\n" + r.after;
      const std::string why = r.read(text, r.file);
      EXPECT_EQ(why.rfind(std::string(r.file) + ":2: " + r.field + ": ", 0), 0u) << why;
    }
  }
}

// The same files with an ordinary value are accepted, so the refusals above are the value's.
TEST(TomlNumberReaders, EveryReaderAcceptsAnOrdinaryValue) {
  for (const ReaderCase& r : kReaders) {
    if (!r.ordinary) continue;  // taps.toml: n_point_calibration_test reads whole tap files
    const std::string key = std::string(r.field).substr(std::string(r.field).find('.') + 1);
    SCOPED_TRACE(std::string(r.field) + " = " + r.ordinary);
    EXPECT_EQ(r.read(std::string(r.before) + key + " = " + r.ordinary + "\n" + r.after, r.file),
              "");
  }
}

}  // namespace
}  // namespace cb
