// `cloudbrush bench smoothing`: jitter at rest and lag in motion for raw samples, a 4-sample
// moving average and the 1€ filter as configured (calibration defaults unless a profile or
// options say otherwise), and the error of the predicted preview against no prediction, on the
// committed synthetic strokes with known ground truth (calibration/bench_strokes: 200 Hz,
// position noise sigma 0.05 mm, pressure noise sigma 0.5 %). Baselines are raw / moving
// average / unpredicted, measured in the same run. Never fails on a missed target.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "app/bench/bench_report.h"
#include "app/bench/benches.h"
#include "app/cli/args.h"
#include "calibration/calibration_profile.h"
#include "calibration/calibrator.h"
#include "calibration/smoothing_metrics.h"
#include "calibration/synthetic_stroke.h"
#include "drivers/core/journal.h"

namespace cb {
namespace {

constexpr size_t kSkip = 100;  // 0.5 s of filter start-up left out of every figure

struct FilterOutputs {
  std::vector<glm::dvec2> truth, raw, ma4, one_euro;
  std::vector<TimedPoint> truth_t, filtered_t, preview_t;
  int contact_changes = 0;
  double ns_per_sample = 0.0, ma4_ns_per_sample = 0.0;
};

// A device whose millimetres are pixels, so the calibrator's output is in mm.
PenDeviceInfo millimetreDevice() {
  PenDeviceInfo d;
  d.x_max = 400;
  d.y_max = 300;
  d.x_res = d.y_res = 1.0;
  d.pressure_max = 2047;
  return d;
}

FilterOutputs runStroke(const SyntheticStroke& stroke, const CalibrationProfile& base) {
  CalibrationProfile profile = base;
  profile.area = AreaMappingConfig{};
  profile.area.fit = AreaFit::kStretch;
  profile.fit_kind = PointFitKind::kNone;
  FilterOutputs out;
  std::vector<PenSample> pen;
  for (const StrokeSample& s : stroke.samples) {
    PenSample p;
    p.t_ns = s.t_ns;
    p.x_mm = s.x_mm;
    p.y_mm = s.y_mm;
    p.pressure = s.pressure;
    p.buttons = kPenTip;
    p.in_proximity = true;
    p.tool = PenTool::kPen;
    pen.push_back(p);
    out.truth.push_back({s.true_x_mm, s.true_y_mm});
    out.truth_t.push_back({s.t_ns, {s.true_x_mm, s.true_y_mm}});
    out.raw.push_back({s.x_mm, s.y_mm});
  }
  // Timing: the median over repeats of the time per sample, construction excluded.
  using Clock = std::chrono::steady_clock;
  constexpr int kRepeats = 21;  // outputs kept from the first run
  std::vector<double> ma_ns, cal_ns;
  for (int rep = 0; rep < kRepeats; ++rep) {
    MovingAverageFilter ma(4);
    Calibrator cal(profile, millimetreDevice(), 400, 300);
    std::vector<glm::dvec2> ma_out(pen.size());
    std::vector<MappedSample> cal_out(pen.size());
    const auto t0 = Clock::now();
    for (size_t i = 0; i < pen.size(); ++i) ma_out[i] = ma.filter({pen[i].x_mm, pen[i].y_mm});
    const auto t1 = Clock::now();
    for (size_t i = 0; i < pen.size(); ++i) cal_out[i] = cal.process(pen[i]);
    const auto t2 = Clock::now();
    ma_ns.push_back(std::chrono::duration<double, std::nano>(t1 - t0).count() / pen.size());
    cal_ns.push_back(std::chrono::duration<double, std::nano>(t2 - t1).count() / pen.size());
    if (rep != 0) continue;
    out.ma4 = ma_out;
    bool contact = false;
    for (size_t i = 0; i < cal_out.size(); ++i) {
      const MappedSample& m = cal_out[i];
      if (i > 0 && m.contact != contact) ++out.contact_changes;
      contact = m.contact;
      out.one_euro.push_back({m.x_px, m.y_px});
      out.filtered_t.push_back({m.t_ns, {m.x_px, m.y_px}});
      out.preview_t.push_back({m.t_ns, {m.preview_x_px, m.preview_y_px}});
    }
  }
  out.ma4_ns_per_sample = median(ma_ns);
  out.ns_per_sample = median(cal_ns);
  return out;
}

// A recorded trace (a journal) has no ground truth: jitter is measured over still windows of
// contact (the raw position stays within 0.5 mm for 0.4 s) and lag against the raw samples
// themselves over moving stretches of contact (mean speed above 50 mm/s for 0.3 s).
int benchTrace(const std::string& path, const CalibrationProfile& base) {
  JournalReadResult j = readJournal(path);
  if (!j.error.empty()) std::fprintf(stderr, "cloudbrush bench smoothing: %s\n", j.error.c_str());
  PenDeviceInfo device = millimetreDevice();
  std::vector<PenSample> pen;
  for (const JournalRecord& r : j.records) {
    if (r.type == JournalRecordType::kDevice) {
      if (auto d = decodeDeviceInfo(r.payload)) {
        device.pressure_max = d->pressure_max;
        device.distance_max = d->distance_max;
      }
    } else if (r.type == JournalRecordType::kPenSample) {
      if (auto s = decodePenSample(r.payload)) pen.push_back(*s);
    }
  }
  if (pen.size() < 100) {
    std::fprintf(stderr, "cloudbrush bench smoothing: %s: only %zu pen samples\n", path.c_str(),
                 pen.size());
    return 2;
  }
  device.x_max = device.y_max = 1000;  // 1 unit per mm on a 1000 px screen: px = mm
  CalibrationProfile profile = base;
  profile.area = AreaMappingConfig{};
  profile.area.fit = AreaFit::kStretch;
  profile.fit_kind = PointFitKind::kNone;
  Calibrator cal(profile, device, 1000, 1000);
  MovingAverageFilter ma(4);
  // Contact segments, each a run of (raw, ma4, 1-euro) positions.
  struct Segment {
    std::vector<int64_t> t;
    std::vector<glm::dvec2> raw, ma4, euro;
  };
  std::vector<Segment> segments;
  bool in_contact = false;
  for (const PenSample& s : pen) {
    const MappedSample m = cal.process(s);
    if (m.contact_began || (m.contact && !in_contact)) {
      segments.emplace_back();
      ma.reset();
    }
    in_contact = m.contact;
    if (!m.contact) continue;
    Segment& seg = segments.back();
    seg.t.push_back(s.t_ns);
    seg.raw.push_back({s.x_mm, s.y_mm});
    seg.ma4.push_back(ma.filter({s.x_mm, s.y_mm}));
    seg.euro.push_back({m.x_px, m.y_px});
  }
  double jr = 0, jm = 0, je = 0, lag_m = 0, lag_e = 0, speed = 0;
  int still = 0, moving = 0;
  for (const Segment& seg : segments) {
    const size_t n = seg.t.size();
    for (size_t i = 0; i < n;) {
      // Grow a window while it stays still.
      size_t k = i;
      glm::dvec2 lo = seg.raw[i], hi = seg.raw[i];
      while (k + 1 < n) {
        const glm::dvec2 l2 = glm::min(lo, seg.raw[k + 1]), h2 = glm::max(hi, seg.raw[k + 1]);
        if (glm::length(h2 - l2) > 0.5) break;
        lo = l2, hi = h2, ++k;
      }
      if ((seg.t[k] - seg.t[i]) * 1e-9 >= 0.4) {
        auto slice = [&](const std::vector<glm::dvec2>& v) {
          return std::vector<glm::dvec2>(v.begin() + i + 10, v.begin() + k + 1);  // settle 10
        };
        jr += jitterStdMm(slice(seg.raw), 0);
        jm += jitterStdMm(slice(seg.ma4), 0);
        je += jitterStdMm(slice(seg.euro), 0);
        ++still;
      }
      i = k + 1;
    }
    const double dur = n > 1 ? (seg.t.back() - seg.t.front()) * 1e-9 : 0.0;
    if (dur >= 0.3) {
      double len = 0;
      for (size_t i = 1; i < n; ++i) len += glm::length(seg.raw[i] - seg.raw[i - 1]);
      if (len / dur > 50.0) {
        const double dt = dur / static_cast<double>(n - 1);
        lag_m += lagByCrossCorrelation(seg.raw, seg.ma4, dt, 10, 20) * 1e3;
        lag_e += lagByCrossCorrelation(seg.raw, seg.euro, dt, 10, 20) * 1e3;
        speed += len / dur;
        ++moving;
      }
    }
  }
  BenchReport report("smoothing");
  report.note("trace", path);
  std::printf("trace %s: %zu samples, %zu strokes, %d still windows, %d moving strokes\n",
              path.c_str(), pen.size(), segments.size(), still, moving);
  if (still > 0) {
    std::printf("jitter at rest (per-axis std, mm):   raw %.4f   ma4 %.4f   1-euro %.4f\n",
                jr / still, jm / still, je / still);
    report.baseline("trace_jitter_rest_mm_raw", jr / still);
    report.baseline("trace_jitter_rest_mm_ma4", jm / still);
    report.figure("trace_jitter_rest_mm_one_euro", je / still);
  }
  if (moving > 0) {
    std::printf("lag behind the raw samples at %.0f mm/s mean (ms):   ma4 %.2f   1-euro %.2f\n",
                speed / moving, lag_m / moving, lag_e / moving);
    report.figure("trace_mean_speed_mm_s", speed / moving);
    report.baseline("trace_lag_ms_ma4", lag_m / moving);
    report.figure("trace_lag_ms_one_euro", lag_e / moving);
  }
  report.print();
  return 0;
}

int usage(int code) {
  std::printf(
      "usage: cloudbrush bench smoothing [--strokes DIR] [--profile FILE] [--min-cutoff HZ]\n"
      "                                  [--beta B] [--d-cutoff HZ] [--velocity-cutoff HZ]\n"
      "                                  [--horizon MS] [--write-strokes DIR] [--trace JOURNAL]\n"
      "  --strokes DIR        committed strokes (default %s)\n"
      "  --profile FILE       take smoothing/prediction settings from a calibration profile\n"
      "  --min-cutoff, --beta, --d-cutoff   1-euro position parameters (mm, Hz)\n"
      "  --velocity-cutoff, --horizon       prediction parameters\n"
      "  --trace JOURNAL      measure on a recorded session instead (no ground truth: jitter\n"
      "                       over still windows, lag against the raw samples)\n"
      "  --write-strokes DIR  regenerate the synthetic strokes into DIR and exit\n"
      "  --seed-offset N      with --write-strokes: other noise seeds (a held-out set)\n",
      benchStrokesDir().c_str());
  return code;
}

// --write-strokes DIR: the synthetic strokes regenerated into DIR (with --seed-offset N, other
// noise seeds: a held-out set).
int writeBenchStrokes(Args& args, const std::string& dir) {
  std::filesystem::create_directories(dir);
  const long seed_offset = args.getInt("seed-offset", 0);  // != 0: a held-out set
  for (StrokeSpec spec : benchStrokeSpecs()) {
    spec.seed += static_cast<uint64_t>(seed_offset);
    const std::string path = dir + "/" + spec.name + ".csv";
    std::ofstream(path) << formatStrokeCsv(makeSyntheticStroke(spec));
    std::printf("wrote %s\n", path.c_str());
  }
  return 0;
}

// The filter's settings: a calibration profile's (--profile) or the defaults, then the
// parameters given. -1 when they hold, else the exit status.
int readSmoothingProfile(Args& args, CalibrationProfile* profile) {
  if (auto path = args.get("profile")) {
    ProfileParseResult r = readCalibrationProfile(*path);
    for (const auto& e : r.errors) std::fprintf(stderr, "%s\n", e.c_str());
    if (!r.profile) return 2;
    *profile = *r.profile;
  }
  auto& e = profile->smoothing.position;
  e.min_cutoff_hz = args.getDouble("min-cutoff", e.min_cutoff_hz);
  e.beta = args.getDouble("beta", e.beta);
  e.d_cutoff_hz = args.getDouble("d-cutoff", e.d_cutoff_hz);
  profile->prediction.velocity_cutoff_hz =
      args.getDouble("velocity-cutoff", profile->prediction.velocity_cutoff_hz);
  profile->prediction.horizon_ms = args.getDouble("horizon", profile->prediction.horizon_ms);
  if (!args.error().empty()) {
    std::fprintf(stderr, "cloudbrush bench smoothing: %s\n", args.error().c_str());
    return 2;
  }
  return -1;
}

// The preview error at the prediction horizon on the 300 mm/s strokes: raw, filtered without
// prediction and predicted. The smallest ratio unpredicted / predicted, returned.
double benchPreviewError(std::map<std::string, FilterOutputs>& runs,
                         const CalibrationProfile& profile, BenchReport& report) {
  const double horizon_s = profile.prediction.horizon_ms * 1e-3;
  double worst_ratio = 1e9;
  for (const char* name : {"circle_300", "wave_300"}) {
    const FilterOutputs& r = runs[name];
    const double unpredicted = previewErrorMm(r.truth_t, r.filtered_t, horizon_s, kSkip);
    const double predicted = previewErrorMm(r.truth_t, r.preview_t, horizon_s, kSkip);
    const double raw_unpredicted = previewErrorMm(
        r.truth_t,
        [&] {
          std::vector<TimedPoint> v;
          for (size_t i = 0; i < r.raw.size(); ++i) v.push_back({r.truth_t[i].t_ns, r.raw[i]});
          return v;
        }(),
        horizon_s, kSkip);
    std::printf(
        "preview error at %.0f ms on %s (mm): raw %.3f   filtered, unpredicted %.3f   "
        "predicted %.3f  (%.1fx smaller)\n",
        profile.prediction.horizon_ms, name, raw_unpredicted, unpredicted, predicted,
        unpredicted / predicted);
    report.baseline(std::string("preview_error_mm_") + name + "_raw", raw_unpredicted);
    report.baseline(std::string("preview_error_mm_") + name + "_unpredicted", unpredicted);
    report.figure(std::string("preview_error_mm_") + name + "_predicted", predicted);
    worst_ratio = std::min(worst_ratio, unpredicted / predicted);
  }
  return worst_ratio;
}

}  // namespace

int benchSmoothing(int argc, char** argv) {
  Args args(argc, argv, {"help"});
  const std::vector<std::string> known = {"help",  "strokes",       "profile",         "min-cutoff",
                                          "beta",  "d-cutoff",      "velocity-cutoff", "horizon",
                                          "trace", "write-strokes", "seed-offset"};
  if (args.has("help")) return usage(0);
  if (auto bad = args.unknown(known); !bad.empty()) {
    std::fprintf(stderr, "cloudbrush bench smoothing: unknown option %s\n", bad[0].c_str());
    return usage(2);
  }

  if (auto dir = args.get("write-strokes")) return writeBenchStrokes(args, *dir);

  CalibrationProfile profile;
  if (const int status = readSmoothingProfile(args, &profile); status >= 0) return status;
  const auto& e = profile.smoothing.position;

  if (auto trace = args.get("trace")) return benchTrace(*trace, profile);

  const std::string dir = args.get("strokes", benchStrokesDir());
  std::map<std::string, FilterOutputs> runs;
  for (const StrokeSpec& spec : benchStrokeSpecs()) {
    SyntheticStroke stroke;
    std::string err;
    if (!readStrokeCsv(dir + "/" + spec.name + ".csv", &stroke, &err)) {
      std::fprintf(stderr, "cloudbrush bench smoothing: %s\n", err.c_str());
      return 2;
    }
    runs[spec.name] = runStroke(stroke, profile);
  }

  const double dt = 0.005;
  BenchReport report("smoothing");
  std::printf(
      "1-euro position: min_cutoff %.3g Hz, beta %.3g /mm, d_cutoff %.3g Hz; prediction "
      "horizon %.3g ms, velocity cutoff %.3g Hz, lag compensation %s\n",
      e.min_cutoff_hz, e.beta, e.d_cutoff_hz, profile.prediction.horizon_ms,
      profile.prediction.velocity_cutoff_hz,
      profile.prediction.compensate_filter_lag ? "on" : "off");

  const FilterOutputs& rest = runs["rest"];
  const double jit_raw = jitterStdMm(rest.raw, kSkip), jit_ma = jitterStdMm(rest.ma4, kSkip),
               jit_euro = jitterStdMm(rest.one_euro, kSkip);
  std::printf(
      "\njitter at rest (per-axis std, mm):   raw %.4f   ma4 %.4f   1-euro %.4f  "
      "(1-euro cuts it %.1fx)\n",
      jit_raw, jit_ma, jit_euro, jit_raw / jit_euro);
  report.baseline("jitter_rest_mm_raw", jit_raw);
  report.baseline("jitter_rest_mm_ma4", jit_ma);
  report.figure("jitter_rest_mm_one_euro", jit_euro);
  report.figure("jitter_reduction_one_euro_x", jit_raw / jit_euro);

  double lag_euro_300 = 0, lag_ma_300 = 0;
  for (const char* name : {"circle_100", "circle_300"}) {
    const FilterOutputs& r = runs[name];
    const std::string speed = std::string(name).substr(7);
    const double lr = lagByCrossCorrelation(r.truth, r.raw, dt, kSkip) * 1e3;
    const double lm = lagByCrossCorrelation(r.truth, r.ma4, dt, kSkip) * 1e3;
    const double le = lagByCrossCorrelation(r.truth, r.one_euro, dt, kSkip) * 1e3;
    std::printf("lag at %s mm/s (ms, cross-correlation): raw %.2f   ma4 %.2f   1-euro %.2f\n",
                speed.c_str(), lr, lm, le);
    report.baseline("lag_" + speed + "_ms_raw", lr);
    report.baseline("lag_" + speed + "_ms_ma4", lm);
    report.figure("lag_" + speed + "_ms_one_euro", le);
    if (speed == "300") lag_euro_300 = le, lag_ma_300 = lm;
  }

  const double worst_ratio = benchPreviewError(runs, profile, report);

  int chatter = 0;
  for (auto& [name, r] : runs) chatter += r.contact_changes;
  std::printf("contact changes during pressed strokes (pressure noise 0.5 %%): %d\n", chatter);
  report.figure("contact_changes_pressed", chatter);
  const FilterOutputs& c300 = runs["circle_300"];
  std::printf("cost: calibrator %.0f ns/sample (moving average alone %.0f ns/sample)\n",
              c300.ns_per_sample, c300.ma4_ns_per_sample);
  report.figure("calibrator_ns_per_sample", c300.ns_per_sample);
  report.baseline("ma4_ns_per_sample", c300.ma4_ns_per_sample);

  auto verdict = [](bool met) { return met ? "met" : "MISSED"; };
  const bool jitter_ok = jit_raw / jit_euro >= 5.0;
  const bool lag_ok = lag_euro_300 <= 4.0;
  const bool beats_ma = jit_euro < jit_ma && lag_euro_300 < lag_ma_300;
  const bool predict_ok = worst_ratio >= 2.0;
  std::printf(
      "\ntargets: jitter cut >= 5x: %s; lag <= 4 ms at 300 mm/s: %s; beats moving "
      "average on both: %s; prediction halves preview error at 300 mm/s: %s\n",
      verdict(jitter_ok), verdict(lag_ok), verdict(beats_ma), verdict(predict_ok));
  report.note("target_jitter_5x", verdict(jitter_ok));
  report.note("target_lag_4ms_300", verdict(lag_ok));
  report.note("target_beats_ma4", verdict(beats_ma));
  report.note("target_prediction_halves_error", verdict(predict_ok));
  report.print();
  return 0;
}

}  // namespace cb
