#include "app/session/paint_session.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <sstream>

#include "app/mapping/stroke_reach.h"
#include "app/mapping/veil_ink.h"
#include "app/scene/paint_camera.h"
#include "app/session/recorded_settings.h"
#include "app/session/session_replay.h"
#include "app/tools/cloud_animation.h"
#include "app/tools/cloud_morph.h"
#include "app/tools/cloud_morph_cells.h"
#include "app/tools/mesh_loading.h"
#include "app/tools/model_cloud.h"
#include "app/tools/picture_cloud.h"
#include "app/volume/volume_erase.h"
#include "app/volume/volume_file.h"
#include "drivers/core/journal_records.h"

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
         "\ngrid = " + std::to_string(settings.grid) +
         (settings.sky_span != kLegacySkySpan ? "\nsky_span = " + std::to_string(settings.sky_span)
                                              : std::string()) +
         (settings.sky_max_span != settings.sky_span
              ? "\nsky_max_span = " + std::to_string(settings.sky_max_span)
              : std::string()) +
         (settings.placementsGrowSky() ? "\nplacements_grow_sky = true" : std::string()) +
         (settings.veil_ink_left_out ? "\nveil_ink_left_out = true" : std::string()) +
         "\nformat = " + std::to_string(settings.format) +
         (settings.format >= 2
              ? "\nauto_end_still_ms = " + std::to_string(settings.auto_end_still_ms) +
                    "\nauto_end_light_ms = " + std::to_string(settings.auto_end_light_ms)
              : std::string()) +
         "\n";
}

Camera initialPaintCamera(const PaintSessionSettings& settings) {
  if (settings.format < 2) return Camera::reference();
  // The home box (the one-box sky of [-1,1]³, where the bundled cloud sits) framed so that the
  // canvas across it fills the screen; the canvas goes on past it to the sky's edges.
  const Volume box(glm::ivec3(1));
  return defaultPaintCamera(Canvas{}, box.worldMin(), box.worldMax(),
                            float(settings.screen_width) / float(settings.screen_height));
}

bool parseSessionSettings(std::string_view text, PaintSessionSettings* settings,
                          std::string* error) {
  PaintSessionSettings parsed;
  parsed.format = 1;  // records of the first landing have no format key
  parsed.auto_end_still_ms = parsed.auto_end_light_ms = 0;  // nor strokes that end by themselves
  parsed.sky_span = kLegacySkySpan;                         // nor a sky wider than one box
  parsed.sky_max_span = 0;             // nor one that grew: sky_span, set below
  parsed.placements_grow_sky = false;  // nor placements that grew it (before specification 1.5)
  parsed.veil_ink_left_out = false;    // nor veiled ink left out (before specification 1.9)
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
    } else if (key == "sky_span") {
      if (!parseInt(value, 1, kMaxSkySpan, &v))
        return bad(("1.." + std::to_string(kMaxSkySpan)).c_str());
      parsed.sky_span = int(v);
    } else if (key == "sky_max_span") {
      if (!parseInt(value, 1, kMaxSkySpan, &v))
        return bad(("1.." + std::to_string(kMaxSkySpan)).c_str());
      parsed.sky_max_span = int(v);
    } else if (key == "placements_grow_sky") {
      if (value != "true" && value != "false") return bad("true or false");
      parsed.placements_grow_sky = value == "true";
    } else if (key == "veil_ink_left_out") {
      if (value != "true" && value != "false") return bad("true or false");
      parsed.veil_ink_left_out = value == "true";
    } else if (key == "auto_end_still_ms" || key == "auto_end_light_ms") {
      if (!parseInt(value, 0, 600000, &v)) return bad("0..600000 ms");
      (key == "auto_end_still_ms" ? parsed.auto_end_still_ms : parsed.auto_end_light_ms) = int(v);
    } else if (key == "format") {
      if (!parseInt(value, 1, 2, &v))
        return bad("1 or 2 (a newer journal needs a newer cloudbrush)");
      parsed.format = int(v);
    }  // other keys (participant, task, ...) belong to the study, not to the painting
  }
  const std::string sky_problem = parsed.skyExtent().check();
  if (!sky_problem.empty()) return *error = "session: " + sky_problem, false;
  if (parsed.sky_max_span == 0) parsed.sky_max_span = parsed.sky_span;
  if (parsed.sky_max_span < parsed.sky_span)
    return *error = "session: sky_max_span " + std::to_string(parsed.sky_max_span) +
                    " is narrower than sky_span " + std::to_string(parsed.sky_span),
           false;
  *settings = parsed;
  return true;
}

PaintSession::PaintSession(const PaintSessionSettings& settings, const BrushConfig& brush,
                           const MappingConfig& mapping)
    : settings_(settings),
      brush_config_(brush),
      mapping_config_(mapping),
      footprint_w_(std::max(
          1, int(std::lround(settings.screen_width * double(brush.stroke.footprint_scale))))),
      footprint_h_(std::max(
          1, int(std::lround(settings.screen_height * double(brush.stroke.footprint_scale))))),
      sky_(settings.skyExtent()),
      widest_span_(widestSkySpan(settings.grid, settings.sky_span, settings.sky_max_span)),
      volume_(makeSkyVolume(settings.skyExtent())),
      engine_(brush, footprint_w_, footprint_h_),
      mapper_(mapping),
      method_(mapping.method) {
  scene_.camera = initialPaintCamera(settings);
  engine_.setBrushSize(brush.stroke.size);
  applyView();
  history_.reset(volume_);
}

void PaintSession::journalText(JournalRecordType type, int64_t t_ns, const std::string& text) {
  if (journal_ && !journal_->append(type, t_ns, text))
    std::fprintf(stderr, "cloudbrush: journal: %s\n", journal_->error().c_str());
}

void PaintSession::journalFrame(const FrameRecord& record) {
  if (!journal_) return;
  const std::vector<uint8_t> payload = encodeFrameRecord(record);
  if (!journal_->append(JournalRecordType::kFrame, record.present_ns, payload.data(),
                        payload.size()))
    std::fprintf(stderr, "cloudbrush: journal: %s\n", journal_->error().c_str());
}

void PaintSession::recordTo(JournalWriter* journal, int64_t t_ns) {
  journal_ = journal;
  journalText(JournalRecordType::kSession, t_ns, formatSessionSettings(settings_));
  journalText(JournalRecordType::kSettings, t_ns,
              formatSettingsRecord("brush.toml", formatBrushConfig(brush_config_)));
  journalText(JournalRecordType::kSettings, t_ns,
              formatSettingsRecord("mapping.toml", formatMappingConfig(mapping_config_)));
  if (!render_settings_.empty())
    journalText(JournalRecordType::kSettings, t_ns,
                formatSettingsRecord("render.toml", render_settings_));
  journalText(JournalRecordType::kCalibration, t_ns, formatCalibrationProfile(profile_));
  if (journal_ && device_) {
    const std::vector<uint8_t> payload = encodeDeviceInfo(*device_);
    journal_->append(JournalRecordType::kDevice, t_ns, payload.data(), payload.size());
  }
  // The whole starting state, so a replay does not depend on this version's defaults.
  const UiChange start[] = {ui::SetMode{mode_},
                            ui::SetCamera{scene_.camera},
                            ui::SetCanvas{scene_.canvas.altitude, scene_.canvas.thickness},
                            ui::SetLight{scene_.light.direction, scene_.light.colour},
                            ui::SetBrush{engine_.selectedBrush()},
                            ui::SetMapping{method_},
                            ui::SetEraseTool{erase_tool_},
                            ui::SetEraseDiameter{EraseTool::kVacuum, vacuum_diameter_},
                            ui::SetEraseDiameter{EraseTool::kRubOut, rubout_diameter_},
                            ui::SetStyle{style_}};
  // A cloud opened before recording began is where the session starts from.
  if (!opened_source_.empty())
    journalText(JournalRecordType::kMarker, t_ns, "opened " + opened_source_);
  for (const UiChange& change : start) {
    if (settings_.format < 2 && !std::holds_alternative<ui::SetBrush>(change) &&
        !std::holds_alternative<ui::SetMapping>(change))
      continue;  // format 1 knew brush and method only
    const UiRecordText record = formatUiChange(change);
    journalText(record.type, t_ns, record.text);
  }
  // The brush size, when it is not the size of journals before it existed (those replay at 1).
  if (engine_.brushSize() != 1.0f) {
    const UiRecordText record = formatUiChange(ui::SetBrushSize{engine_.brushSize()});
    journalText(record.type, t_ns, record.text);
  }
  // A pressure range set before recording began (the kiosk's, from the operator's press
  // calibration); the whole range is the default and is not written.
  if (pressure_range_.lo != 0.0f || pressure_range_.hi != 1.0f) {
    const UiRecordText record =
        formatUiChange(ui::SetPressureRange{pressure_range_.lo, pressure_range_.hi});
    journalText(record.type, t_ns, record.text);
  }
}

void PaintSession::setRenderSettings(const std::string& render_toml, int64_t t_ns) {
  if (render_toml == render_settings_) return;
  render_settings_ = render_toml;
  journalText(JournalRecordType::kSettings, t_ns, formatSettingsRecord("render.toml", render_toml));
}

void PaintSession::markSync(const std::string& kind, const std::string& label, int64_t t_ns) {
  SyncMarker marker;
  marker.seq = ++sync_seq_;
  marker.kind = kind;
  marker.mono_ns = t_ns;
  if (!reproducible_record_) {
    // The wall clock at the event: now, less the event's age on the session's clock.
    timespec wall{}, mono{};
    clock_gettime(CLOCK_REALTIME, &wall);
    clock_gettime(CLOCK_MONOTONIC, &mono);
    int64_t age_ns = 0;
    if (sync_now_ns_) {
      age_ns = sync_now_ns_() - t_ns;
    } else {
      // Without the session's clock, pen timestamps on CLOCK_MONOTONIC; a time on another time
      // line (a recording fed as fast as read) counts as now.
      age_ns = int64_t(mono.tv_sec) * 1'000'000'000 + mono.tv_nsec - t_ns;
      if (age_ns < 0 || age_ns > 60'000'000'000) age_ns = 0;
    }
    marker.wall_ns = int64_t(wall.tv_sec) * 1'000'000'000 + wall.tv_nsec - age_ns;
  }
  marker.label = label;
  const std::string text = formatSyncMarker(marker);
  if (sync_sender_) sync_sender_->send(text);
  journalText(JournalRecordType::kSync, t_ns, text);
}

void PaintSession::resumeRecordingTo(JournalWriter* journal) {
  journal_ = journal;
  resuming_ = true;
}

void PaintSession::setDevice(const PenDeviceInfo& device, int64_t t_ns) {
  if (resuming_ && device_ && encodeDeviceInfo(*device_) == encodeDeviceInfo(device)) return;
  device_ = device;
  calibrator_.reset();
  if (journal_) {
    const std::vector<uint8_t> payload = encodeDeviceInfo(device);
    if (!journal_->append(JournalRecordType::kDevice, t_ns, payload.data(), payload.size()))
      std::fprintf(stderr, "cloudbrush: journal: %s\n", journal_->error().c_str());
  }
}

void PaintSession::setCalibration(const CalibrationProfile& profile, int64_t t_ns) {
  if (resuming_ && formatCalibrationProfile(profile_) == formatCalibrationProfile(profile)) return;
  profile_ = profile;
  calibrator_.reset();
  journalText(JournalRecordType::kCalibration, t_ns, formatCalibrationProfile(profile));
}

void PaintSession::applyView() {
  engine_.setPaintView(PaintView{scene_.camera}, scene_.canvas);
}

void PaintSession::recordStep(const SceneState& before, const std::string& label) {
  history_.record(volume_, before, scene_, label);
}

void PaintSession::mapFinishedStroke(SampleOutcome* outcome, int64_t t_ns) {
  StrokeResult stroke;
  while (engine_.takeFinishedStroke(&stroke)) {
    if (settings_.veil_ink_left_out) {
      const SkyExtent widest = reachableSky();
      outcome->veil_pixels += leaveOutVeiledInk(&stroke, widest.worldMin(), widest.worldMax(),
                                                mapper_.config().circles.empty_threshold);
    }
    if (growSkyToHold([&](const Volume& sky) {
          const glm::vec3 voxel = sky.voxelSize();
          return strokeReach(stroke, mapper_.config(), std::min({voxel.x, voxel.y, voxel.z}));
        }))
      last_growth_stroke_ = stroke.stroke_index;
    // The stroke ended at this sample: other recorders hear it before the mapping's time.
    markSync("stroke_end", std::to_string(stroke.stroke_index), t_ns);
    // §6: the finished footprint becomes voxels, max-merged; the stroke index seeds the noise.
    outcome->mapping = mapper_.map(stroke, volume_, method_);
    outcome->stroke_mapped = true;
    outcome->stroke_index = stroke.stroke_index;
    ++strokes_mapped_;
    recordStep(scene_, "stroke " + std::to_string(stroke.stroke_index));
    // A measurement, not an input: replay skips it and measures its own.
    if (!reproducible_record_)
      journalText(JournalRecordType::kStrokeMapped, t_ns,
                  formatStrokeMapped(stroke.stroke_index, outcome->mapping.timings.total_ms));
    syncJournal();
  }
}

bool PaintSession::growSkyToHold(const std::function<SkyReach(const Volume&)>& reach_of) {
  bool grew = false;
  while (widest_span_ > sky_.span) {
    // A reach whose rectangle is unknown (a stroke's ray missing the canvas is placed on the
    // mapping's fallback plane, possibly far off) makes the sky as wide as it may be.
    const SkyExtent to = skyToHold(sky_, widest_span_, reach_of(volume_));
    if (to.span <= sky_.span) break;
    const glm::ivec3 offset = growthOffset(sky_, to);
    volume_ = growSky(std::move(volume_), sky_, to);
    history_.followGrowth(volume_, offset / Volume::kBrickSize);
    sky_ = to;
    ++sky_growths_;
    grew = true;
  }
  return grew;
}

void PaintSession::syncJournal() {
  // Every completed stroke is on the disk before the next one begins.
  if (journal_ && !journal_->sync())
    std::fprintf(stderr, "cloudbrush: journal: %s\n", journal_->error().c_str());
}

float PaintSession::rubOutDiameterAt(float pressure) const {
  return rubout_diameter_ * std::clamp(0.25f + 0.75f * pressure, 0.25f, 1.0f);
}

bool PaintSession::vacuumCentre(const MappedSample& sample, glm::vec3* centre) const {
  glm::vec3 origin, dir;
  scene_.camera.pixelRay(float(sample.x_px), float(sample.y_px), settings_.screen_width,
                         settings_.screen_height, &origin, &dir);
  float t = 0.0f;
  if (!scene_.canvas.intersectMidPlane(origin, dir, &t)) return false;
  const glm::vec3 on_plane = origin + t * dir;
  const float lo = volume_.worldMin().y, hi = volume_.worldMax().y;
  *centre =
      glm::vec3(on_plane.x, lo + std::clamp(sample.pressure, 0.0f, 1.0f) * (hi - lo), on_plane.z);
  return true;
}

void PaintSession::takeFrame(const WindowFrame& frame) {
  // Only the bricks whose bytes differ are written and marked, so the renderer uploads and the
  // history keeps those alone.
  pasteVolume(frame.volume, frame.volume.bounds(), frame.at, &volume_);
}

bool PaintSession::commitAnimation(const UiChange& change, const WindowFrame& shown, int64_t t_ns,
                                   std::string* error) {
  const bool morph = std::holds_alternative<ui::ApplyMorph>(change);
  if (!morph && !std::holds_alternative<ui::ApplyWind>(change))
    return *error = "apply: not an animation", false;
  // The frame must be a window of this sky, over that window's world box.
  const VoxelBox box{shown.at, shown.at + shown.volume.dims()};
  glm::vec3 world_min, world_max;
  windowWorldBox(volume_, box, &world_min, &world_max);
  if (box.intersect(volume_.bounds()) != box || shown.volume.worldMin() != world_min ||
      shown.volume.worldMax() != world_max)
    return *error = "apply: the animated cloud does not fit this sky; the cloud is unchanged",
           false;
  if (engine_.inStroke()) return *error = "apply: a stroke is being painted", false;
  const SceneState before = scene_;
  takeFrame(shown);
  recordStep(before, morph ? "morph" : "wind");
  const UiRecordText record = formatUiChange(change);
  journalText(record.type, t_ns, record.text);
  return true;
}

bool PaintSession::replaceVolume(const Volume& volume, int64_t t_ns, const std::string& source,
                                 std::string* error) {
  // A cloud of the one-box sky (grid³ over [-1,1]³) opens in the home box of the sky as it is;
  // a saved sky opens as it was saved when this session's sky could have grown to it.
  const bool home_box = isHomeBoxCloud(volume, sky_);
  const std::optional<SkyExtent> saved_sky = skyExtentOf(volume);
  const bool fits = saved_sky && saved_sky->grid == sky_.grid && saved_sky->span >= sky_.span &&
                    saved_sky->span <= widest_span_;
  if (!home_box && !fits) {
    const glm::ivec3 d = volume_.dims(), w = reachableSky().dims();
    *error = source + ": a " + std::to_string(volume.dims().x) + "x" +
             std::to_string(volume.dims().y) + "x" + std::to_string(volume.dims().z) +
             " cloud does not fit this session's " + std::to_string(d.x) + "x" +
             std::to_string(d.y) + "x" + std::to_string(d.z) + " sky" +
             (w != d ? " (which may grow to " + std::to_string(w.x) + "x" + std::to_string(w.y) +
                           "x" + std::to_string(w.z) + ")"
                     : std::string()) +
             ", nor its " + std::to_string(sky_.grid) + "³ home box; the cloud is unchanged";
    return false;
  }
  if (engine_.inStroke()) return *error = "open: a stroke is being painted", false;
  if (home_box) {
    volume_ = placeInSky(volume, sky_);
  } else {
    volume_ = volume;
    sky_ = *saved_sky;
  }
  history_.reset(volume_);
  opened_source_ = source;
  journalText(JournalRecordType::kMarker, t_ns, "opened " + source);
  return true;
}

SampleOutcome PaintSession::feed(const PenSample& sample) {
  SampleOutcome outcome;
  resuming_ = false;
  if (journal_ && !journal_->appendPenSample(sample))
    std::fprintf(stderr, "cloudbrush: journal: %s\n", journal_->error().c_str());
  if (!device_) {
    ++samples_without_device_;
    return outcome;
  }
  if (!calibrator_) {
    calibrator_ = std::make_unique<Calibrator>(profile_, *device_, settings_.screen_width,
                                               settings_.screen_height);
    calibrator_->setPressureRange(pressure_range_);
    calibrator_error_ = calibrator_->error();
    if (!calibrator_->ok())
      std::fprintf(stderr, "cloudbrush: calibration: %s\n", calibrator_error_.c_str());
  }
  outcome.mapped = calibrator_->process(sample);
  const MappedSample& m = outcome.mapped;
  if (pen_captured_) {
    // The UI holds the pen: calibrated (the filters keep running) but nothing drawn.
  } else if (mode_ == Mode::kPaint) {
    if (held_until_lift_) {
      if (!m.contact) held_until_lift_ = false;  // lifted: the next touch starts a stroke
      return outcome;
    }
    const bool was_in_stroke = engine_.inStroke();
    outcome.changed = engine_.feedCalibrated(m);
    outcome.stroke_began = !was_in_stroke && engine_.inStroke();
    if (outcome.stroke_began)
      markSync("stroke_begin", std::to_string(engine_.nextStrokeIndex() - 1), m.t_ns);
    if (engine_.inStroke()) {
      // §7.7.5 problem 3: a stroke left open ends by itself (times from the samples, so a
      // replay ends the same strokes).
      const glm::vec2 at(float(m.x_px), float(m.y_px));
      if (outcome.stroke_began || glm::length(at - still_anchor_) >= 2.0f) {
        still_anchor_ = at;
        still_since_ns_ = m.t_ns;
      }
      // Light: held down by the calibration's hysteresis alone (calibration/mapped_sample.h),
      // or, for journals recorded before stroke.auto_end_light_by_hysteresis, under 5%.
      const bool light_touch =
          brush_config_.stroke.auto_end_light_by_hysteresis ? m.light_contact : m.pressure < 0.05f;
      if (!light_touch)
        light_since_ns_ = -1;
      else if (light_since_ns_ < 0)
        light_since_ns_ = m.t_ns;
      const bool still = settings_.auto_end_still_ms > 0 &&
                         m.t_ns - still_since_ns_ >= int64_t(settings_.auto_end_still_ms) * 1000000;
      const bool light = settings_.auto_end_light_ms > 0 && light_since_ns_ >= 0 &&
                         m.t_ns - light_since_ns_ >= int64_t(settings_.auto_end_light_ms) * 1000000;
      if (still || light) {
        engine_.finishStroke();
        held_until_lift_ = true;
        light_since_ns_ = -1;
        outcome.auto_ended = true;
      }
    }
    mapFinishedStroke(&outcome, m.t_ns);
  } else if (mode_ == Mode::kErase && erase_tool_ == EraseTool::kRubOut) {
    // §3.5.2: while the tip is down, a cylinder along the view through the canvas's height
    // range, its diameter from the pressure.
    if (m.contact) {
      glm::vec3 origin, dir;
      scene_.camera.pixelRay(float(m.x_px), float(m.y_px), settings_.screen_width,
                             settings_.screen_height, &origin, &dir);
      outcome.erased = !rubOutCylinder(volume_, origin, dir, 0.5f * rubOutDiameterAt(m.pressure),
                                       scene_.canvas.bottom(), scene_.canvas.top())
                            .empty();
      rubbing_ = true;
    }
    if (rubbing_ && (m.contact_ended || !m.contact)) {
      rubbing_ = false;
      recordStep(scene_, "rub-out");
      syncJournal();
    }
  }
  return outcome;
}

// apply's handler of each typed change: true when it applied, else false with *error said.
struct PaintSession::Applier {
  PaintSession& s;
  std::string* error;
  const SceneState& before;
  int64_t t_ns;
  bool operator()(const ui::SetMode& c);
  bool operator()(const ui::SetCamera& c) {
    s.scene_.camera = c.camera;
    s.applyView();
    s.recordStep(before, "camera");
    return true;
  }
  bool operator()(const ui::SetBrush& c) {
    s.engine_.selectBrush(c.brush);
    return true;
  }
  bool operator()(const ui::SetBrushSize& c) {
    s.engine_.setBrushSize(c.size);
    return true;
  }
  bool operator()(const ui::SetMapping& c) {
    s.method_ = c.method;
    return true;
  }
  bool operator()(const ui::SetCanvas& c) {
    s.scene_.canvas.altitude = c.altitude;
    s.scene_.canvas.thickness = c.thickness;
    s.applyView();
    s.recordStep(before, "canvas");
    return true;
  }
  bool operator()(const ui::SetLight& c) {
    s.scene_.light.direction = glm::normalize(c.direction);
    s.scene_.light.colour = c.colour;
    s.recordStep(before, "light");
    return true;
  }
  bool operator()(const ui::SetEraseTool& c) {
    s.erase_tool_ = c.tool;
    return true;
  }
  bool operator()(const ui::SetEraseDiameter& c) {
    (c.tool == EraseTool::kVacuum ? s.vacuum_diameter_ : s.rubout_diameter_) = c.diameter;
    return true;
  }
  bool operator()(const ui::VacuumCut& c) {
    vacuumSphere(s.volume_, c.centre, c.radius);
    s.recordStep(before, "vacuum");
    return true;
  }
  bool operator()(const ui::PlaceShape& c);
  bool operator()(const ui::ApplyMorph& c);
  bool operator()(const ui::ApplyWind& c);
  bool operator()(const ui::SetStyle& c) {
    s.style_ = c.name;
    return true;
  }
  bool operator()(const ui::SetPressureRange& c) {
    s.pressure_range_ = PressureRange{c.lo, c.hi};
    if (s.calibrator_) s.calibrator_->setPressureRange(s.pressure_range_);
    return true;
  }
  bool operator()(const ui::PenCapture& c) {
    if (c.captured && (s.engine_.inStroke() || s.rubbing_))
      return *error = "pen capture: the pen is drawing", false;
    s.pen_captured_ = c.captured;
    return true;
  }
  bool operator()(const ui::ShowMenu& c) {
    s.menu_open_ = c.open;
    return true;
  }
  bool operator()(const ui::Undo&) {
    if (s.engine_.inStroke()) return *error = "undo: a stroke is being painted", false;
    SceneState restored;
    if (!s.history_.undo(&s.volume_, &restored)) return *error = "undo: nothing to undo", false;
    s.scene_ = restored;
    s.applyView();
    return true;
  }
  bool operator()(const ui::Redo&) {
    if (s.engine_.inStroke()) return *error = "redo: a stroke is being painted", false;
    SceneState restored;
    if (!s.history_.redo(&s.volume_, &restored)) return *error = "redo: nothing to redo", false;
    s.scene_ = restored;
    s.applyView();
    return true;
  }
  bool operator()(const ui::DeleteAll&) {
    if (s.engine_.inStroke()) return *error = "delete: a stroke is being painted", false;
    s.volume_.fill(0.0f);
    s.recordStep(before, "delete all");
    return true;
  }
};

bool PaintSession::Applier::operator()(const ui::SetMode& c) {
  if (s.engine_.inStroke() && c.mode != Mode::kPaint) {
    // The stroke in progress ends where it is, as if the pen lifted.
    SampleOutcome outcome;
    s.engine_.finishStroke();
    s.mapFinishedStroke(&outcome, t_ns);
  }
  if (s.rubbing_) {
    s.rubbing_ = false;
    s.recordStep(s.scene_, "rub-out");
  }
  s.mode_ = c.mode;
  return true;
}

bool PaintSession::Applier::operator()(const ui::PlaceShape& c) {
  if (s.engine_.inStroke()) return *error = "place: a stroke is being painted", false;
  // Seen from the paint view at the canvas altitude; seeded by the step count, so a replay
  // places the same cloud.
  ToolView view{s.scene_.camera, s.settings_.screen_width, s.settings_.screen_height,
                s.scene_.canvas};
  // The file is read and checked first; then, when placements grow the sky (the Session
  // record's placements_grow_sky), the sky grows to hold where the cloud can write, as for a
  // stroke; then the cloud is written.
  const bool grow = s.settings_.placementsGrowSky();
  try {
    if (c.model) {
      const TriangleMesh mesh = loadClosedMesh(c.path);
      if (grow)
        s.growSkyToHold(
            [&](const Volume& sky) { return placementReach(modelReach(mesh, view, sky), sky); });
      ModelCloudParams params;
      params.seed = uint32_t(s.history_.steps() + 1);
      meshToCloud(mesh, view, params, &s.volume_);
    } else {
      const ShapeMask mask = loadShapeMask(c.path);
      PictureCloudParams params;
      params.seed = uint32_t(s.history_.steps() + 1);
      if (grow)
        s.growSkyToHold([&](const Volume& sky) {
          return placementReach(pictureReach(mask, view, params, sky), sky);
        });
      maskToCloud(mask, view, params, &s.volume_);
    }
  } catch (const std::exception& e) {
    return *error = std::string(c.model ? "model" : "picture") + ": " + e.what() +
                    "; the cloud is unchanged",
           false;
  }
  s.recordStep(before, c.model ? "model" : "picture");
  return true;
}

bool PaintSession::Applier::operator()(const ui::ApplyMorph& c) {
  if (s.engine_.inStroke()) return *error = "morph: a stroke is being painted", false;
  try {
    const Volume target = loadMorphTarget(c.target, s.volume_);
    const uint64_t checksum = volumeChecksum(target);
    if (checksum != c.target_checksum) {
      char text[96];
      std::snprintf(text, sizeof text, " (checksum %016llx, recorded %016llx)",
                    (unsigned long long)checksum, (unsigned long long)c.target_checksum);
      return *error = "morph: the target " + c.target + " is not the cloud morphed into" + text +
                      "; the cloud is unchanged",
             false;
    }
    // A `morph=` record (specification 1.1) is recomputed the way it was made.
    s.takeFrame(c.cell_blocks ? WindowFrame{morphCellBlocks(s.volume_, target, c.t)}
                              : morphFrame(s.volume_, target, c.t));
  } catch (const std::exception& e) {
    return *error = std::string("morph: ") + e.what() + "; the cloud is unchanged", false;
  }
  s.recordStep(before, "morph");
  return true;
}

bool PaintSession::Applier::operator()(const ui::ApplyWind& c) {
  if (s.engine_.inStroke()) return *error = "wind: a stroke is being painted", false;
  if (c.step_by_step) {
    Volume blown = s.volume_;
    blowWindStepByStep(c.run, &blown);
    s.takeFrame(WindowFrame{std::move(blown)});
  } else {
    s.takeFrame(windFrame(c.run, s.volume_));
  }
  s.recordStep(before, "wind");
  return true;
}

bool PaintSession::apply(const UiChange& change, int64_t t_ns, std::string* error) {
  std::string ignored;
  if (!error) error = &ignored;
  const SceneState before = scene_;
  if (!std::visit(Applier{*this, error, before, t_ns}, change)) return false;
  const UiRecordText record = formatUiChange(change);
  journalText(record.type, t_ns, record.text);
  return true;
}

// A Session record: the recording's settings must be this session's.
bool PaintSession::applySessionRecord(const JournalRecord& record, std::string* error) {
  PaintSessionSettings recorded;
  if (!parseSessionSettings(record.text(), &recorded, error)) return false;
  if (recorded.screen_width != settings_.screen_width ||
      recorded.screen_height != settings_.screen_height || recorded.grid != settings_.grid ||
      recorded.sky_span != settings_.sky_span || recorded.sky_max_span != settings_.sky_max_span ||
      recorded.placementsGrowSky() != settings_.placementsGrowSky() ||
      recorded.veil_ink_left_out != settings_.veil_ink_left_out ||
      recorded.format != settings_.format ||
      recorded.auto_end_still_ms != settings_.auto_end_still_ms ||
      recorded.auto_end_light_ms != settings_.auto_end_light_ms) {
    *error = "session record (" + formatSessionSettings(recorded) +
             ") differs from this session's settings";
    return false;
  }
  journalText(JournalRecordType::kSession, record.t_ns, std::string(record.text()));
  return true;
}

// A Settings record: render.toml is applied; brush.toml and mapping.toml must be the settings
// this session was made with.
bool PaintSession::applySettingsRecord(const JournalRecord& record, std::string* error) {
  std::string name, body;
  if (!parseSettingsRecord(record.text(), &name, &body, error)) return false;
  if (name == "render.toml") {
    setRenderSettings(body, record.t_ns);
    return true;
  }
  // Compared as read back (recorded_settings.h): an older text lacks keys added since, or
  // carries retired ones, yet stands for the same settings.
  std::string in_force, recorded;
  if (name == "brush.toml") {
    BrushConfig parsed;
    std::vector<std::string> errors;
    if (!parseRecordedBrush(body, name, &parsed, &errors))
      return *error = errors.empty() ? name : errors.front(), false;
    in_force = formatBrushConfig(brush_config_);
    recorded = formatBrushConfig(parsed);
  } else if (name == "mapping.toml") {
    try {
      recorded = formatMappingConfig(parseRecordedMapping(body, name));
    } catch (const std::exception& e) {
      return *error = e.what(), false;
    }
    in_force = formatMappingConfig(mapping_config_);
  } else {
    return true;  // a config this version does not record: skipped
  }
  if (recorded != in_force) {
    *error = "settings record " + name +
             " differs from the settings this session was made with (replaySession makes "
             "the session from the recorded ones)";
    return false;
  }
  journalText(record.type, record.t_ns, std::string(record.text()));
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
    case JournalRecordType::kSession:
      return applySessionRecord(record, error);
    case JournalRecordType::kUi:
    case JournalRecordType::kMode: {
      if (record.type == JournalRecordType::kMode && settings_.format < 2) {
        journalText(record.type, record.t_ns, std::string(record.text()));
        return true;  // format 1 wrote "paint" once, for information
      }
      UiChange change;
      if (!parseUiChange(record.type, record.text(), &change, error)) return false;
      return apply(change, record.t_ns, error);
    }
    case JournalRecordType::kSettings:
      return applySettingsRecord(record, error);
    case JournalRecordType::kSync:
      // An output of the session, made again as it runs; the numbering carries on after it.
      if (const std::optional<SyncMarker> marker = parseSyncMarker(record.text()))
        sync_seq_ = std::max(sync_seq_, marker->seq);
      return true;
    case JournalRecordType::kStrokeMapped:
    case JournalRecordType::kFrame:
      return true;  // a measurement of the recording run; this run measures its own
    case JournalRecordType::kMarker:
      if (record.text().rfind("opened ", 0) == 0) {
        // The session opened a saved cloud here: replay needs that file where it was.
        const std::string path(record.text().substr(7));
        try {
          return replaceVolume(loadVolume(path), record.t_ns, path, error);
        } catch (const std::exception& e) {
          *error = std::string("the session opened ") + path + " here: " + e.what();
          return false;
        }
      }
      journalText(record.type, record.t_ns, std::string(record.text()));
      return true;
  }
  return true;  // a type this version does not know: skipped, as the reader does
}

}  // namespace cb
