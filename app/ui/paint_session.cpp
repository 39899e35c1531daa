#include "app/ui/paint_session.h"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace cb {
namespace {

std::string trim(std::string_view text) {
  size_t b = 0, e = text.size();
  while (b < e && std::isspace(static_cast<unsigned char>(text[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(text[e - 1]))) --e;
  return std::string(text.substr(b, e - b));
}

bool parseInt(const std::string& text, long lo, long hi, long* out) {
  char* end = nullptr;
  const long v = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || v < lo || v > hi) return false;
  *out = v;
  return true;
}

}  // namespace

std::string formatSessionSettings(const PaintSessionSettings& settings) {
  return "screen_width = " + std::to_string(settings.screen_width) +
         "\nscreen_height = " + std::to_string(settings.screen_height) +
         "\ngrid = " + std::to_string(settings.grid) + "\n";
}

bool parseSessionSettings(std::string_view text, PaintSessionSettings* settings,
                          std::string* error) {
  PaintSessionSettings parsed;
  std::istringstream lines{std::string(text)};
  std::string line;
  for (int number = 1; std::getline(lines, line); ++number) {
    const std::string content = trim(line.substr(0, line.find('#')));
    if (content.empty()) continue;
    const size_t eq = content.find('=');
    const std::string key = eq == std::string::npos ? content : trim(content.substr(0, eq));
    const std::string value = eq == std::string::npos ? "" : trim(content.substr(eq + 1));
    long v = 0;
    const auto bad = [&](const char* expected) {
      *error = "session line " + std::to_string(number) + ": " + key + ": expected " + expected +
               ", got '" + value + "'";
      return false;
    };
    if (key == "screen_width") {
      if (!parseInt(value, 1, 16384, &v)) return bad("1..16384");
      parsed.screen_width = int(v);
    } else if (key == "screen_height") {
      if (!parseInt(value, 1, 16384, &v)) return bad("1..16384");
      parsed.screen_height = int(v);
    } else if (key == "grid") {
      if (!parseInt(value, 8, 1024, &v)) return bad("8..1024");
      parsed.grid = int(v);
    }  // other keys (participant, task, ...) belong to the study, not to the painting
  }
  *settings = parsed;
  return true;
}

PaintSession::PaintSession(const PaintSessionSettings& settings, const BrushConfig& brush,
                           const MappingConfig& mapping)
    : settings_(settings),
      footprint_w_(std::max(
          1, int(std::lround(settings.screen_width * double(brush.stroke.footprint_scale))))),
      footprint_h_(std::max(
          1, int(std::lround(settings.screen_height * double(brush.stroke.footprint_scale))))),
      volume_(glm::ivec3(settings.grid)),
      engine_(brush, footprint_w_, footprint_h_),
      mapper_(mapping),
      method_(mapping.method) {
  applyView();
}

void PaintSession::journalText(JournalRecordType type, int64_t t_ns, const std::string& text) {
  if (journal_ && !journal_->append(type, t_ns, text))
    std::fprintf(stderr, "cloudbrush: journal: %s\n", journal_->error().c_str());
}

void PaintSession::recordTo(JournalWriter* journal, int64_t t_ns) {
  journal_ = journal;
  journalText(JournalRecordType::kSession, t_ns, formatSessionSettings(settings_));
  journalText(JournalRecordType::kMode, t_ns, "paint");
  journalText(JournalRecordType::kCalibration, t_ns, formatCalibrationProfile(profile_));
  if (journal_ && device_) {
    const std::vector<uint8_t> payload = encodeDeviceInfo(*device_);
    journal_->append(JournalRecordType::kDevice, t_ns, payload.data(), payload.size());
  }
  if (orbit_degrees_ != 0.0f) {
    char text[64];
    std::snprintf(text, sizeof text, "camera_orbit=%.9g", double(orbit_degrees_));
    journalText(JournalRecordType::kUi, t_ns, text);
  }
  journalText(JournalRecordType::kUi, t_ns,
              std::string("brush=") + brushKindName(engine_.selectedBrush()));
  journalText(JournalRecordType::kUi, t_ns, std::string("method=") + toString(method_));
}

void PaintSession::setDevice(const PenDeviceInfo& device, int64_t t_ns) {
  device_ = device;
  calibrator_.reset();
  if (journal_) {
    const std::vector<uint8_t> payload = encodeDeviceInfo(device);
    if (!journal_->append(JournalRecordType::kDevice, t_ns, payload.data(), payload.size()))
      std::fprintf(stderr, "cloudbrush: journal: %s\n", journal_->error().c_str());
  }
}

void PaintSession::setCalibration(const CalibrationProfile& profile, int64_t t_ns) {
  profile_ = profile;
  calibrator_.reset();
  journalText(JournalRecordType::kCalibration, t_ns, formatCalibrationProfile(profile));
}

void PaintSession::applyView() {
  camera_ = Camera::reference().orbited(orbit_degrees_);
  engine_.setPaintView(PaintView{camera_}, canvas_);
}

SampleOutcome PaintSession::feed(const PenSample& sample) {
  SampleOutcome outcome;
  if (journal_ && !journal_->appendPenSample(sample))
    std::fprintf(stderr, "cloudbrush: journal: %s\n", journal_->error().c_str());
  if (!device_) {
    ++samples_without_device_;
    return outcome;
  }
  if (!calibrator_) {
    calibrator_ = std::make_unique<Calibrator>(profile_, *device_, settings_.screen_width,
                                               settings_.screen_height);
    calibrator_error_ = calibrator_->error();
    if (!calibrator_->ok())
      std::fprintf(stderr, "cloudbrush: calibration: %s\n", calibrator_error_.c_str());
  }
  outcome.mapped = calibrator_->process(sample);
  const bool was_in_stroke = engine_.inStroke();
  outcome.changed = engine_.feedCalibrated(outcome.mapped);
  outcome.stroke_began = !was_in_stroke && engine_.inStroke();
  StrokeResult stroke;
  if (engine_.takeFinishedStroke(&stroke)) {
    // §6: the finished footprint becomes voxels, max-merged; the stroke index seeds the noise.
    outcome.mapping = mapper_.map(stroke, volume_, method_);
    outcome.stroke_mapped = true;
    outcome.stroke_index = stroke.stroke_index;
    ++strokes_mapped_;
  }
  return outcome;
}

bool PaintSession::applyUi(const std::string& key_value, int64_t t_ns, std::string* error) {
  const size_t eq = key_value.find('=');
  if (eq == std::string::npos) {
    *error = "UI change '" + key_value + "': expected key=value";
    return false;
  }
  const std::string key = key_value.substr(0, eq), value = key_value.substr(eq + 1);
  if (key == "camera_orbit") {
    char* end = nullptr;
    const float degrees = std::strtof(value.c_str(), &end);
    if (value.empty() || *end != '\0' || !std::isfinite(degrees)) {
      *error = "UI change camera_orbit: expected degrees, got '" + value + "'";
      return false;
    }
    orbit_degrees_ = degrees;
    applyView();
  } else if (key == "brush") {
    BrushKind kind;
    if (!parseBrushKind(value, &kind)) {
      *error = "UI change brush: expected 2d, 3d or skeleton, got '" + value + "'";
      return false;
    }
    engine_.selectBrush(kind);
  } else if (key == "method") {
    MappingMethod method;
    if (!parseMappingMethod(value, &method)) {
      *error = "UI change method: expected hybrid or ray-marching, got '" + value + "'";
      return false;
    }
    method_ = method;
  } else {
    *error = "UI change '" + key_value + "': unknown key '" + key + "'";
    return false;
  }
  journalText(JournalRecordType::kUi, t_ns, key_value);
  return true;
}

bool PaintSession::applyRecord(const JournalRecord& record, SampleOutcome* outcome,
                               std::string* error) {
  switch (record.type) {
    case JournalRecordType::kPenSample: {
      const std::optional<PenSample> sample = decodePenSample(record.payload);
      if (!sample) {
        *error =
            "pen sample record of " + std::to_string(record.payload.size()) + " bytes (wrong size)";
        return false;
      }
      const SampleOutcome result = feed(*sample);
      if (outcome) *outcome = result;
      return true;
    }
    case JournalRecordType::kDevice: {
      const std::optional<PenDeviceInfo> device = decodeDeviceInfo(record.payload);
      if (!device) {
        *error =
            "device record of " + std::to_string(record.payload.size()) + " bytes (wrong size)";
        return false;
      }
      setDevice(*device, record.t_ns);
      return true;
    }
    case JournalRecordType::kCalibration: {
      ProfileParseResult parsed = parseCalibrationProfile(record.text(), "calibration record");
      if (!parsed.profile) {
        *error = parsed.errors.empty() ? "calibration record does not parse" : parsed.errors[0];
        return false;
      }
      setCalibration(*parsed.profile, record.t_ns);
      return true;
    }
    case JournalRecordType::kSession: {
      PaintSessionSettings recorded;
      if (!parseSessionSettings(record.text(), &recorded, error)) return false;
      if (recorded.screen_width != settings_.screen_width ||
          recorded.screen_height != settings_.screen_height || recorded.grid != settings_.grid) {
        *error = "session record (" + formatSessionSettings(recorded) +
                 ") differs from this session's settings";
        return false;
      }
      journalText(JournalRecordType::kSession, record.t_ns, std::string(record.text()));
      return true;
    }
    case JournalRecordType::kUi:
      return applyUi(std::string(record.text()), record.t_ns, error);
    case JournalRecordType::kMode:
    case JournalRecordType::kMarker:
      journalText(record.type, record.t_ns, std::string(record.text()));
      return true;
  }
  return true;  // a type this version does not know: skipped, as the reader does
}

}  // namespace cb
