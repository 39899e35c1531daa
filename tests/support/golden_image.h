// A rendered image against its golden PNG: every channel of every pixel within `max_pixel` and
// the mean within `max_mean` (llvmpipe's rounding differs by a few levels between machines, so
// the tests name their bounds). CB_UPDATE_GOLDENS=1 rewrites the golden instead (review and
// commit it); on a mismatch the image is written as NAME.actual.png in the working directory.
// Header-only: the golden tests link the renderer alone.
#pragma once

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "app/render/image_io.h"

namespace cb::test {

inline void expectImageMatchesGolden(const std::string& golden_path, const std::string& name,
                                     const ImageRgba8& image, int max_pixel, double max_mean) {
  if (std::getenv("CB_UPDATE_GOLDENS")) {
    writePng(golden_path, image);
    std::printf("updated %s\n", golden_path.c_str());
    return;
  }
  ASSERT_TRUE(std::filesystem::exists(golden_path))
      << "no golden " << golden_path << " (CB_UPDATE_GOLDENS=1 creates it)";
  const ImageRgba8 golden = readPng(golden_path);
  ASSERT_EQ(golden.width, image.width);
  ASSERT_EQ(golden.height, image.height);
  int worst = 0;
  double sum = 0;
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    const int e = std::abs(int(image.pixels[i]) - int(golden.pixels[i]));
    worst = std::max(worst, e);
    sum += e;
  }
  const double mean = sum / double(image.pixels.size());
  if (worst > max_pixel || mean > max_mean) writePng(name + ".actual.png", image);
  EXPECT_LE(worst, max_pixel) << name << ": worst channel error (see " << name << ".actual.png)";
  EXPECT_LE(mean, max_mean) << name << ": mean channel error";
}

}  // namespace cb::test
