#include "brush_test_support.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include "calibration/contact_hysteresis.h"

namespace cb::test {

StrokeResult paintStroke(StrokeEngine* engine, const std::vector<BrushInput>& samples) {
  // Contact as calibration/'s hysteresis decides it (the engine decides none), with the
  // thresholds the committed goldens were painted with: down at 2 %, up below 1 %.
  ContactHysteresis contact(ContactThresholds{0.02f, 0.01f});
  engine->prepareNextStroke();
  for (const BrushInput& in : samples) {
    const bool was_down = contact.down();
    if (contact.update(in.pressure))
      was_down ? engine->addSample(in) : engine->beginStroke(in);
    else if (was_down)
      break;  // lifted
  }
  return engine->endStroke();
}

int inkedPixels(const Footprint& fp, float threshold) {
  int n = 0;
  for (float v : fp.values) n += v > threshold;
  return n;
}

double inkSum(const Footprint& fp) {
  double s = 0.0;
  for (float v : fp.values) s += v;
  return s;
}

double meanAbsDifference(const Footprint& a, const Footprint& b) {
  double s = 0.0;
  for (size_t i = 0; i < a.values.size(); ++i) s += std::abs(a.values[i] - b.values[i]);
  return s / double(a.values.size());
}

double inkIoU(const Footprint& a, const Footprint& b, float t) {
  size_t both = 0, either = 0;
  for (size_t i = 0; i < a.values.size(); ++i) {
    bool x = a.values[i] > t, y = b.values[i] > t;
    both += x && y;
    either += x || y;
  }
  return either ? double(both) / double(either) : 1.0;
}

void combineMax(const Footprint& src, Footprint* dst) {
  for (size_t i = 0; i < src.values.size(); ++i)
    dst->values[i] = std::max(dst->values[i], src.values[i]);
}

Footprint quantise8(const Footprint& fp) {
  Footprint q = fp;
  for (float& v : q.values) v = std::round(std::clamp(v, 0.0f, 1.0f) * 255.0f) / 255.0f;
  return q;
}

bool writePgm(const std::string& path, const Footprint& fp, std::string* error) {
  std::ofstream f(path, std::ios::binary);
  if (!f) {
    *error = "cannot write " + path;
    return false;
  }
  f << "P5\n" << fp.width << " " << fp.height << "\n255\n";
  for (float v : fp.values) f.put(char(uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f))));
  return bool(f);
}

bool readPgm(const std::string& path, Footprint* fp, std::string* error) {
  std::ifstream f(path, std::ios::binary);
  if (!f) {
    *error = "cannot open " + path;
    return false;
  }
  std::string magic;
  int w = 0, h = 0, maxval = 0;
  f >> magic >> w >> h >> maxval;
  f.get();
  if (magic != "P5" || w <= 0 || h <= 0 || maxval != 255) {
    *error = path + ": not an 8-bit binary PGM";
    return false;
  }
  *fp = Footprint(w, h);
  for (float& v : fp->values) {
    int c = f.get();
    if (c == EOF) {
      *error = path + ": truncated";
      return false;
    }
    v = float(c) / 255.0f;
  }
  return true;
}

}  // namespace cb::test
