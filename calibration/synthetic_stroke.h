// Synthetic pen strokes with known ground truth, for measuring smoothing and prediction
// (`cloudbrush bench smoothing`) and in tests. A stroke is sampled at a fixed report rate;
// every sample keeps the true position and pressure next to the noisy one the "device"
// reports (Gaussian position noise per axis in mm, Gaussian pressure noise), seeded, so the
// same parameters always give the same stroke. Strokes are committed as CSV files under
// calibration/bench_strokes/ and read back with readStrokeCsv().
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace cb {

struct StrokeSample {
  int64_t t_ns = 0;
  double true_x_mm = 0, true_y_mm = 0;
  float true_pressure = 0;
  double x_mm = 0, y_mm = 0;  // as reported: truth + noise
  float pressure = 0;
};

struct SyntheticStroke {
  std::string name;
  std::vector<StrokeSample> samples;
};

enum class StrokeShape {
  kRest,    // the pen held still (pressed) at the centre
  kCircle,  // a circle of `size_mm` radius at constant speed
  kWave,    // a sine wave, wavelength 4 * size_mm and amplitude size_mm / 2, advancing so the
            // mean speed along the path is `speed_mm_s`
};

struct StrokeSpec {
  std::string name;
  StrokeShape shape = StrokeShape::kRest;
  double speed_mm_s = 0.0;
  double size_mm = 40.0;
  double duration_s = 3.0;
  double rate_hz = 200.0;
  double position_noise_mm = 0.05;  // sigma per axis
  double pressure_noise = 0.005;    // sigma, fraction of full range
  float pressure = 0.5f;            // true pressure while pressed
  double centre_x_mm = 100.0, centre_y_mm = 80.0;
  uint64_t seed = 1;
};

SyntheticStroke makeSyntheticStroke(const StrokeSpec& spec);

// The committed set: rest, circles at 100 and 300 mm/s, a wave at 300 mm/s (200 Hz,
// sigma 0.05 mm, pressure sigma 0.5 %).
std::vector<StrokeSpec> benchStrokeSpecs();

// Where the committed strokes live: $CLOUDBRUSH_BENCH_STROKES, else calibration/bench_strokes
// in the source tree this was built from.
std::string benchStrokesDir();

// CSV: a header line, then t_ns,true_x_mm,true_y_mm,true_pressure,x_mm,y_mm,pressure.
std::string formatStrokeCsv(const SyntheticStroke& stroke);
// Returns false with *error naming the file and line on malformed input.
bool readStrokeCsv(const std::string& path, SyntheticStroke* stroke, std::string* error);
bool parseStrokeCsv(const std::string& text, const std::string& name, SyntheticStroke* stroke,
                    std::string* error);

}  // namespace cb
