#include "app/session/ui_change.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace cb {
namespace {

constexpr const char* kModeNames[] = {"camera", "canvas", "paint", "erase", "light"};

std::string formatFloats(const float* values, size_t n) {
  std::string out;
  char buffer[32];
  for (size_t i = 0; i < n; ++i) {
    std::snprintf(buffer, sizeof buffer, "%s%.9g", i ? "," : "", double(values[i]));
    out += buffer;
  }
  return out;
}

// Exactly `n` comma-separated finite floats.
bool parseFloats(std::string_view text, size_t n, float* out) {
  std::vector<float> values;
  std::string rest(text);
  size_t start = 0;
  while (true) {
    const size_t comma = rest.find(',', start);
    const std::string field =
        rest.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    char* end = nullptr;
    const float v = std::strtof(field.c_str(), &end);
    if (field.empty() || *end != '\0' || !std::isfinite(v)) return false;
    values.push_back(v);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (values.size() != n) return false;
  for (size_t i = 0; i < n; ++i) out[i] = values[i];
  return true;
}

}  // namespace

const char* modeName(Mode mode) {
  return kModeNames[int(mode)];
}

bool parseMode(std::string_view text, Mode* out) {
  for (int i = 0; i < 5; ++i)
    if (text == kModeNames[i]) {
      *out = Mode(i);
      return true;
    }
  return false;
}

const char* cameraMoveName(CameraMove move) {
  constexpr const char* kNames[] = {"set", "orbit", "pan", "zoom", "view"};
  return kNames[int(move)];
}

const char* eraseToolName(EraseTool tool) {
  return tool == EraseTool::kVacuum ? "vacuum" : "rub-out";
}

UiRecordText formatUiChange(const UiChange& change) {
  struct Formatter {
    UiRecordText operator()(const ui::SetMode& c) const {
      return {JournalRecordType::kMode, modeName(c.mode)};
    }
    UiRecordText operator()(const ui::SetCamera& c) const {
      const float v[7] = {c.camera.eye.x,    c.camera.eye.y,    c.camera.eye.z,
                          c.camera.target.x, c.camera.target.y, c.camera.target.z,
                          c.camera.fov_y_deg};
      // The move is an optional last field, so records written before it existed still parse
      // (as kSet) and a plain set reads as it always did.
      return {JournalRecordType::kUi,
              "camera=" + formatFloats(v, 7) +
                  (c.move == CameraMove::kSet ? "" : std::string(",") + cameraMoveName(c.move))};
    }
    UiRecordText operator()(const ui::SetBrush& c) const {
      return {JournalRecordType::kUi, std::string("brush=") + brushKindName(c.brush)};
    }
    UiRecordText operator()(const ui::SetBrushSize& c) const {
      return {JournalRecordType::kUi, "brush_size=" + formatFloats(&c.size, 1)};
    }
    UiRecordText operator()(const ui::SetMapping& c) const {
      return {JournalRecordType::kUi, std::string("method=") + toString(c.method)};
    }
    UiRecordText operator()(const ui::SetCanvas& c) const {
      const float v[2] = {c.altitude, c.thickness};
      return {JournalRecordType::kUi, "canvas=" + formatFloats(v, 2)};
    }
    UiRecordText operator()(const ui::SetLight& c) const {
      const float v[6] = {c.direction.x, c.direction.y, c.direction.z,
                          c.colour.r,    c.colour.g,    c.colour.b};
      return {JournalRecordType::kUi, "light=" + formatFloats(v, 6)};
    }
    UiRecordText operator()(const ui::SetEraseTool& c) const {
      return {JournalRecordType::kUi, std::string("erase_tool=") + eraseToolName(c.tool)};
    }
    UiRecordText operator()(const ui::SetEraseDiameter& c) const {
      return {JournalRecordType::kUi,
              std::string(c.tool == EraseTool::kVacuum ? "vacuum_diameter=" : "rubout_diameter=") +
                  formatFloats(&c.diameter, 1)};
    }
    UiRecordText operator()(const ui::VacuumCut& c) const {
      const float v[4] = {c.centre.x, c.centre.y, c.centre.z, c.radius};
      return {JournalRecordType::kUi, "vacuum_cut=" + formatFloats(v, 4)};
    }
    UiRecordText operator()(const ui::PenCapture& c) const {
      return {JournalRecordType::kUi, std::string("pen_capture=") + (c.captured ? "on" : "off")};
    }
    UiRecordText operator()(const ui::ShowMenu& c) const {
      return {JournalRecordType::kUi, std::string("menu=") + (c.open ? "open" : "closed")};
    }
    UiRecordText operator()(const ui::SetPressureRange& c) const {
      const float v[2] = {c.lo, c.hi};
      return {JournalRecordType::kUi, "pressure_range=" + formatFloats(v, 2)};
    }
    UiRecordText operator()(const ui::PlaceShape& c) const {
      return {JournalRecordType::kUi, (c.model ? "place_model=" : "place_picture=") + c.path};
    }
    UiRecordText operator()(const ui::SetStyle& c) const {
      return {JournalRecordType::kUi, "style=" + c.name};
    }
    UiRecordText operator()(const ui::ApplyMorph& c) const {
      char checksum[24];
      std::snprintf(checksum, sizeof checksum, "%016llx", (unsigned long long)c.target_checksum);
      return {JournalRecordType::kUi, std::string(c.cell_blocks ? "morph=" : "morph2=") +
                                          formatFloats(&c.t, 1) + "," + checksum + "," + c.target};
    }
    UiRecordText operator()(const ui::ApplyWind& c) const {
      const float head[2] = {c.run.speed, c.run.gust};
      std::string text = (c.step_by_step ? "wind=" : "wind2=") + formatFloats(head, 2);
      for (const WindSegment& s : c.run.segments) {
        const float d[2] = {s.dx, s.dz};
        text += ";" + formatFloats(d, 2) + "," + std::to_string(s.steps);
      }
      return {JournalRecordType::kUi, text};
    }
    UiRecordText operator()(const ui::Undo&) const { return {JournalRecordType::kUi, "undo"}; }
    UiRecordText operator()(const ui::Redo&) const { return {JournalRecordType::kUi, "redo"}; }
    UiRecordText operator()(const ui::DeleteAll&) const {
      return {JournalRecordType::kUi, "delete_all"};
    }
  };
  return std::visit(Formatter{}, change);
}

namespace {

// A UI change whose value does not parse: the message names the key, what was expected and
// what came.
struct BadValue {
  const std::string& key;
  const std::string& value;
  std::string* error;
  bool operator()(const char* expected) const {
    *error = "UI change " + key + ": expected " + expected + ", got '" + value + "'";
    return false;
  }
};

// camera=EX,EY,EZ,TX,TY,TZ,FOV[,MOVE]
bool parseCameraChange(const std::string& value, const BadValue& bad, UiChange* out) {
  float v[7];
  std::string numbers = value;
  CameraMove move = CameraMove::kSet;
  const size_t last = value.rfind(',');
  if (last != std::string::npos && last + 1 < value.size() && std::isalpha(value[last + 1])) {
    const std::string name = value.substr(last + 1);
    bool known = false;
    for (int m = 0; m <= int(CameraMove::kView); ++m)
      if (name == cameraMoveName(CameraMove(m))) move = CameraMove(m), known = true;
    if (!known) return bad("a camera move orbit, pan, zoom or view after the numbers");
    numbers = value.substr(0, last);
  }
  if (!parseFloats(numbers, 7, v) || v[6] <= 0.0f || v[6] >= 180.0f)
    return bad("EX,EY,EZ,TX,TY,TZ,FOV[,MOVE] (fov in (0, 180) degrees)");
  Camera camera = Camera::reference();
  camera.eye = {v[0], v[1], v[2]};
  camera.target = {v[3], v[4], v[5]};
  camera.fov_y_deg = v[6];
  if (glm::length(camera.eye - camera.target) <= 0.0f) return bad("an eye apart from the target");
  *out = ui::SetCamera{camera, move};
  return true;
}

// morph= / morph2=T,CHECKSUM,TARGET (morph: the cell-block morph; morph2: the whole-frame one).
bool parseMorphChange(const std::string& key, const std::string& value, const BadValue& bad,
                      UiChange* out) {
  // T,CHECKSUM,TARGET (the target last: a path may hold commas).
  const size_t c1 = value.find(','), c2 = c1 == std::string::npos ? c1 : value.find(',', c1 + 1);
  ui::ApplyMorph morph;
  char* end = nullptr;
  const std::string hex = c2 == std::string::npos ? "" : value.substr(c1 + 1, c2 - c1 - 1);
  if (c2 == std::string::npos || !parseFloats(value.substr(0, c1), 1, &morph.t) || morph.t < 0.0f ||
      morph.t > 1.0f || hex.size() != 16)
    return bad("T,CHECKSUM,TARGET (t in [0, 1], a 16-digit hex checksum, a path)");
  morph.target_checksum = std::strtoull(hex.c_str(), &end, 16);
  morph.target = value.substr(c2 + 1);
  morph.cell_blocks = key == "morph";
  if (*end != '\0' || morph.target.empty() || morph.target.find('\n') != std::string::npos)
    return bad("T,CHECKSUM,TARGET (t in [0, 1], a 16-digit hex checksum, a path)");
  *out = morph;
  return true;
}

// wind= / wind2=SPEED,GUST;DX,DZ,STEPS;... (wind: blown step by step).
bool parseWindChange(const std::string& key, const std::string& value, const BadValue& bad,
                     UiChange* out) {
  float v[2];
  ui::ApplyWind wind;
  wind.step_by_step = key == "wind";
  size_t start = 0;
  for (int part = 0; start <= value.size(); ++part) {
    const size_t semi = value.find(';', start);
    const std::string field =
        value.substr(start, semi == std::string::npos ? std::string::npos : semi - start);
    if (part == 0) {
      if (!parseFloats(field, 2, v) || v[0] < 0.0f || v[0] > 100.0f || std::abs(v[1]) > 1000.0f)
        return bad("SPEED,GUST;DX,DZ,STEPS;... (speed in [0, 100])");
      wind.run.speed = v[0];
      wind.run.gust = v[1];
    } else {
      const size_t last = field.rfind(',');
      char* end = nullptr;
      const long steps =
          last == std::string::npos ? -1 : std::strtol(field.c_str() + last + 1, &end, 10);
      if (last == std::string::npos || !parseFloats(field.substr(0, last), 2, v) || *end != '\0' ||
          steps < 0 || steps > 100000)
        return bad("SPEED,GUST;DX,DZ,STEPS;... (0..100000 steps per segment)");
      wind.run.segments.push_back({v[0], v[1], int(steps)});
    }
    if (semi == std::string::npos) break;
    start = semi + 1;
  }
  if (wind.run.segments.empty() || wind.run.steps() > 100000)
    return bad("SPEED,GUST;DX,DZ,STEPS;... (at least one segment, at most 100000 steps)");
  *out = wind;
  return true;
}

}  // namespace

bool parseUiChange(JournalRecordType type, std::string_view text, UiChange* out,
                   std::string* error) {
  if (type == JournalRecordType::kMode) {
    Mode mode;
    if (!parseMode(text, &mode)) {
      *error = "mode record: expected camera, canvas, paint, erase or light, got '" +
               std::string(text) + "'";
      return false;
    }
    *out = ui::SetMode{mode};
    return true;
  }
  if (type != JournalRecordType::kUi) {
    *error = "not a UI or mode record";
    return false;
  }
  if (text == "undo") return *out = ui::Undo{}, true;
  if (text == "redo") return *out = ui::Redo{}, true;
  if (text == "delete_all") return *out = ui::DeleteAll{}, true;
  const size_t eq = text.find('=');
  if (eq == std::string_view::npos) {
    *error = "UI change '" + std::string(text) + "': expected key=value, undo, redo or delete_all";
    return false;
  }
  const std::string key(text.substr(0, eq));
  const std::string value(text.substr(eq + 1));
  const BadValue bad{key, value, error};
  float v[7];
  if (key == "camera") {
    return parseCameraChange(value, bad, out);
  } else if (key == "camera_orbit") {
    if (!parseFloats(value, 1, v)) return bad("degrees");
    *out = ui::SetCamera{Camera::reference().orbited(v[0])};
  } else if (key == "brush") {
    BrushKind kind;
    if (!parseBrushKind(value, &kind)) return bad("2d, 3d or skeleton");
    *out = ui::SetBrush{kind};
  } else if (key == "brush_size") {
    if (!parseFloats(value, 1, v) || v[0] < kMinBrushSize || v[0] > kMaxBrushSize)
      return bad("a size in [0.25, 8]");
    *out = ui::SetBrushSize{v[0]};
  } else if (key == "method") {
    MappingMethod method;
    if (!parseMappingMethod(value, &method)) return bad("hybrid, ray-marching or sheet");
    *out = ui::SetMapping{method};
  } else if (key == "canvas") {
    if (!parseFloats(value, 2, v) || v[1] <= 0.0f) return bad("ALTITUDE,THICKNESS (thickness > 0)");
    *out = ui::SetCanvas{v[0], v[1]};
  } else if (key == "light") {
    if (!parseFloats(value, 6, v) || glm::length(glm::vec3(v[0], v[1], v[2])) <= 0.0f ||
        v[3] < 0.0f || v[4] < 0.0f || v[5] < 0.0f)
      return bad("DX,DY,DZ,R,G,B (a non-zero direction, colours >= 0)");
    *out = ui::SetLight{glm::vec3(v[0], v[1], v[2]), glm::vec3(v[3], v[4], v[5])};
  } else if (key == "erase_tool") {
    if (value == "vacuum")
      *out = ui::SetEraseTool{EraseTool::kVacuum};
    else if (value == "rub-out")
      *out = ui::SetEraseTool{EraseTool::kRubOut};
    else
      return bad("vacuum or rub-out");
  } else if (key == "vacuum_diameter" || key == "rubout_diameter") {
    if (!parseFloats(value, 1, v) || v[0] <= 0.0f) return bad("a diameter > 0");
    *out = ui::SetEraseDiameter{key == "vacuum_diameter" ? EraseTool::kVacuum : EraseTool::kRubOut,
                                v[0]};
  } else if (key == "place_picture" || key == "place_model") {
    if (value.empty() || value.find('\n') != std::string::npos) return bad("a file path");
    *out = ui::PlaceShape{key == "place_model", value};
  } else if (key == "morph" || key == "morph2") {
    return parseMorphChange(key, value, bad, out);
  } else if (key == "wind" || key == "wind2") {
    return parseWindChange(key, value, bad, out);
  } else if (key == "style") {
    bool plain = !value.empty() && value.size() <= 32;
    for (char c : value) plain = plain && c >= 'a' && c <= 'z';
    if (!plain) return bad("a style name (lower-case letters)");
    *out = ui::SetStyle{value};
  } else if (key == "pen_capture") {
    if (value != "on" && value != "off") return bad("on or off");
    *out = ui::PenCapture{value == "on"};
  } else if (key == "menu") {
    if (value != "open" && value != "closed") return bad("open or closed");
    *out = ui::ShowMenu{value == "open"};
  } else if (key == "pressure_range") {
    if (!parseFloats(value, 2, v) || !(v[0] >= 0.0f && v[0] < v[1] && v[1] <= 1.0f))
      return bad("LO,HI (0 <= LO < HI <= 1)");
    *out = ui::SetPressureRange{v[0], v[1]};
  } else if (key == "vacuum_cut") {
    if (!parseFloats(value, 4, v) || v[3] <= 0.0f) return bad("X,Y,Z,RADIUS (radius > 0)");
    *out = ui::VacuumCut{glm::vec3(v[0], v[1], v[2]), v[3]};
  } else {
    *error = "UI change '" + std::string(text) + "': unknown key '" + key + "'";
    return false;
  }
  return true;
}

}  // namespace cb
