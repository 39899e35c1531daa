#include "calibration/synthetic_stroke.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <sstream>

namespace cb {
namespace {

// Box-Muller on a fixed 64-bit generator: std::normal_distribution is not specified
// bit-for-bit across standard libraries, this is.
class GaussianNoise {
 public:
  explicit GaussianNoise(uint64_t seed) : rng_(seed) {}
  double next() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    double u1 = 0.0;
    while (u1 <= 1e-300) u1 = uniform();
    const double u2 = uniform();
    const double r = std::sqrt(-2.0 * std::log(u1));
    spare_ = r * std::sin(2.0 * std::numbers::pi * u2);
    has_spare_ = true;
    return r * std::cos(2.0 * std::numbers::pi * u2);
  }

 private:
  double uniform() { return (rng_() >> 11) * (1.0 / 9007199254740992.0); }
  std::mt19937_64 rng_;
  bool has_spare_ = false;
  double spare_ = 0.0;
};

}  // namespace

SyntheticStroke makeSyntheticStroke(const StrokeSpec& spec) {
  SyntheticStroke stroke;
  stroke.name = spec.name;
  GaussianNoise noise(spec.seed);
  const int n = static_cast<int>(std::lround(spec.duration_s * spec.rate_hz));
  const double r = spec.size_mm;
  for (int i = 0; i < n; ++i) {
    const double t = i / spec.rate_hz;
    StrokeSample s;
    s.t_ns = static_cast<int64_t>(std::llround(t * 1e9));
    double x = spec.centre_x_mm, y = spec.centre_y_mm;
    switch (spec.shape) {
      case StrokeShape::kRest:
        break;
      case StrokeShape::kCircle: {
        const double phase = spec.speed_mm_s * t / r;
        x += r * std::cos(phase);
        y += r * std::sin(phase);
        break;
      }
      case StrokeShape::kWave: {
        // y = A sin(k x) with A = r/2, k = 2 pi / (4 r); arc length per unit x averages
        // about 1.13, so x advances at speed / 1.13 (close enough: the mean speed is reported
        // by the bench from the truth itself).
        const double k = 2.0 * std::numbers::pi / (4.0 * r), a = r / 2.0;
        const double vx = spec.speed_mm_s / 1.13;
        const double u = vx * t - 2.0 * r;
        x += u;
        y += a * std::sin(k * u);
        break;
      }
    }
    s.true_x_mm = x;
    s.true_y_mm = y;
    s.true_pressure = spec.pressure;
    s.x_mm = x + spec.position_noise_mm * noise.next();
    s.y_mm = y + spec.position_noise_mm * noise.next();
    s.pressure = static_cast<float>(spec.pressure + spec.pressure_noise * noise.next());
    stroke.samples.push_back(s);
  }
  return stroke;
}

std::vector<StrokeSpec> benchStrokeSpecs() {
  std::vector<StrokeSpec> specs(4);
  specs[0].name = "rest";
  specs[0].shape = StrokeShape::kRest;
  specs[0].seed = 11;
  specs[1].name = "circle_100";
  specs[1].shape = StrokeShape::kCircle;
  specs[1].speed_mm_s = 100.0;
  specs[1].seed = 12;
  specs[2].name = "circle_300";
  specs[2].shape = StrokeShape::kCircle;
  specs[2].speed_mm_s = 300.0;
  specs[2].seed = 13;
  specs[3].name = "wave_300";
  specs[3].shape = StrokeShape::kWave;
  specs[3].speed_mm_s = 300.0;
  specs[3].size_mm = 30.0;
  specs[3].duration_s = 1.0;
  specs[3].seed = 14;
  return specs;
}

std::string benchStrokesDir() {
  if (const char* env = std::getenv("CLOUDBRUSH_BENCH_STROKES"); env && *env) return env;
  return CB_BENCH_STROKES_DIR;
}

std::string formatStrokeCsv(const SyntheticStroke& stroke) {
  std::string out = "t_ns,true_x_mm,true_y_mm,true_pressure,x_mm,y_mm,pressure\n";
  char buf[256];
  for (const StrokeSample& s : stroke.samples) {
    std::snprintf(buf, sizeof buf, "%lld,%.6f,%.6f,%.5f,%.6f,%.6f,%.5f\n",
                  static_cast<long long>(s.t_ns), s.true_x_mm, s.true_y_mm, s.true_pressure, s.x_mm,
                  s.y_mm, s.pressure);
    out += buf;
  }
  return out;
}

bool parseStrokeCsv(const std::string& text, const std::string& name, SyntheticStroke* stroke,
                    std::string* error) {
  stroke->name = name;
  stroke->samples.clear();
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.empty() || line[0] == '#' || line.rfind("t_ns", 0) == 0) continue;
    double v[7];
    const char* p = line.c_str();
    for (int k = 0; k < 7; ++k) {
      char* end = nullptr;
      errno = 0;
      v[k] = std::strtod(p, &end);
      const bool sep_ok = k < 6 ? *end == ',' : (*end == '\0' || *end == '\r');
      if (end == p || errno != 0 || !sep_ok || !std::isfinite(v[k])) {
        if (error) {
          *error = name + ":" + std::to_string(line_no) + ": field " + std::to_string(k + 1) +
                   " is not a number (want t_ns,true_x_mm,true_y_mm,true_pressure,x_mm,y_mm,"
                   "pressure)";
        }
        return false;
      }
      p = end + 1;
    }
    StrokeSample s;
    s.t_ns = static_cast<int64_t>(v[0]);
    s.true_x_mm = v[1];
    s.true_y_mm = v[2];
    s.true_pressure = static_cast<float>(v[3]);
    s.x_mm = v[4];
    s.y_mm = v[5];
    s.pressure = static_cast<float>(v[6]);
    if (!stroke->samples.empty() && s.t_ns <= stroke->samples.back().t_ns) {
      if (error) *error = name + ":" + std::to_string(line_no) + ": time does not increase";
      return false;
    }
    stroke->samples.push_back(s);
  }
  if (stroke->samples.size() < 2) {
    if (error) *error = name + ": fewer than 2 samples";
    return false;
  }
  return true;
}

bool readStrokeCsv(const std::string& path, SyntheticStroke* stroke, std::string* error) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    if (error) *error = path + ": cannot be opened";
    return false;
  }
  std::stringstream ss;
  ss << in.rdbuf();
  return parseStrokeCsv(ss.str(), path, stroke, error);
}

}  // namespace cb
