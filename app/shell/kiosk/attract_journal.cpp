#include "app/shell/kiosk/attract_journal.h"

#include <vector>

#include "app/session/paint_session.h"
#include "app/session/synthetic_session.h"

namespace cb {
namespace {

constexpr int kW = 1280, kH = 720;  // the screen the strokes were drawn on

SyntheticStroke stroke(std::string name, std::vector<glm::vec2> points, float pressure_low,
                       float pressure_high, float speed) {
  SyntheticStroke s;
  s.name = std::move(name);
  s.control_points = std::move(points);
  s.speed_px_s = speed;
  // Swelling in the middle, like a brush pressed harder through the stroke's body.
  s.pressure = [pressure_low, pressure_high](float t) {
    const float swell = 4.0f * t * (1.0f - t);
    return pressure_low + (pressure_high - pressure_low) * swell;
  };
  return s;
}

std::vector<SyntheticStroke> cumulusStrokes() {
  return {
      stroke("base", {{380, 470}, {520, 480}, {700, 476}, {900, 468}}, 0.35f, 0.8f, 420.0f),
      stroke("left puff", {{420, 462}, {440, 380}, {530, 336}, {610, 410}}, 0.3f, 0.9f, 360.0f),
      stroke("middle puff", {{540, 440}, {580, 310}, {690, 262}, {790, 322}, {810, 440}}, 0.3f,
             1.0f, 360.0f),
      stroke("right puff", {{760, 452}, {800, 372}, {880, 380}, {910, 458}}, 0.3f, 0.85f, 360.0f),
      stroke("wisp", {{600, 404}, {680, 380}, {760, 396}}, 0.2f, 0.5f, 300.0f),
  };
}

}  // namespace

bool writeAttractJournal(const std::string& path, std::string* error) {
  PaintSessionSettings settings;
  settings.screen_width = kW;
  settings.screen_height = kH;
  settings.grid = 128;
  // The bundled loop's strokes all fall in the home box; one box keeps its bytes (and the
  // attract loop's replay) as they were before the sky grew.
  settings.sky_span = settings.sky_max_span = kLegacySkySpan;
  PaintSession recorder(settings, BrushConfig{}, MappingConfig{});
  recorder.setQuietMapping(true);
  recorder.setReproducibleRecord(true);  // the same bytes on every run
  JournalWriter journal;
  if (!journal.open(path)) {
    *error = journal.error();
    return false;
  }
  const PenDeviceInfo tablet = syntheticTablet(kW, kH);
  recorder.setDevice(tablet, 0);
  recorder.recordTo(&journal, 0);
  int64_t t = 1'000'000'000;  // the first stroke one second in
  for (const SyntheticStroke& s : cumulusStrokes()) {
    const std::vector<PenSample> samples = syntheticPenSamples(s, tablet, kW, kH, 200.0, t);
    for (const PenSample& sample : samples) recorder.feed(sample);
    t = samples.back().t_ns + 1'500'000'000;  // a pause between strokes, as a painter's
  }
  recorder.recordTo(nullptr, t);
  if (!journal.sync()) {
    *error = journal.error();
    return false;
  }
  journal.close();
  return true;
}

}  // namespace cb
