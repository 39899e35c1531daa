// Helpers shared by the brush tests: painting a sampled stroke through a StrokeEngine, footprint
// statistics, and 8-bit PGM golden files.
#pragma once

#include <string>
#include <vector>

#include "app/brush/stroke_engine.h"
#include "app/brush/synthetic_strokes.h"

namespace cb::test {

// Feeds the samples through the threshold contact (feed) plus a lifting sample 5 ms later, and
// returns the finished stroke.
StrokeResult paintStroke(StrokeEngine* engine, const std::vector<BrushInput>& samples);

int inkedPixels(const Footprint& fp, float threshold = 0.05f);
double inkSum(const Footprint& fp);
double meanAbsDifference(const Footprint& a, const Footprint& b);
double inkIoU(const Footprint& a, const Footprint& b, float threshold = 0.05f);
// Max-combines `src` into `dst` (same size).
void combineMax(const Footprint& src, Footprint* dst);

// Golden footprints: binary 8-bit PGM (P5), value = round(255 · v).
bool writePgm(const std::string& path, const Footprint& fp, std::string* error);
bool readPgm(const std::string& path, Footprint* fp, std::string* error);
Footprint quantise8(const Footprint& fp);

}  // namespace cb::test
