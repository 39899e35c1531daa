// Fuzz target: the calibration profile parser (outside bytes: profiles are edited by hand and
// copied between kiosks) and the session's pressure-range record (read back from journals).
// A parse that succeeds must format to text that parses back to the same profile.
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "calibration/calibration_profile.h"
#include "calibration/n_point_calibration.h"
#include "calibration/pressure_range.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  cb::ProfileParseResult r = cb::parseCalibrationProfile(text, "fuzz.toml");
  if (r.profile) {
    cb::ProfileParseResult again =
        cb::parseCalibrationProfile(cb::formatCalibrationProfile(*r.profile), "fuzz-again.toml");
    if (!again.profile || !(*again.profile == *r.profile)) std::abort();
  } else if (r.errors.empty()) {
    std::abort();  // no profile must come with a reason
  }
  std::string error;
  (void)cb::pressureRangeFromToml(std::string(text), &error);
  if (!cb::parseTapFile(text, "fuzz-taps.toml", &error) && error.empty()) std::abort();
  return 0;
}
