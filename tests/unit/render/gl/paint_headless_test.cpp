// The main job with no display, run as the real binary: `cloudbrush` must render the bundled
// cloud headlessly, write a PNG and an EXR and print their paths on stdout.
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <ImfArray.h>
#include <ImfRgbaFile.h>
#include <gtest/gtest.h>

#include "app/render/image_io.h"

namespace cb {
namespace {

struct ProcessResult {
  int status = -1;
  std::string out;  // stdout only; stderr goes to err
  std::string err;
};

// Runs the cloudbrush binary in `cwd` with no DISPLAY and no card to take: the headless case.
ProcessResult runCloudbrush(const std::string& cwd, const std::string& args,
                            const std::string& env = "") {
  const std::string err_file = cwd + "/stderr.txt";
  const std::string command = "cd '" + cwd + "' && env -u DISPLAY LIBGL_ALWAYS_SOFTWARE=1 " + env +
                              " '" + CB_CLOUDBRUSH_BIN + "' " + args + " 2>'" + err_file + "'";
  ProcessResult run;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return run;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof(buf), pipe)) > 0) run.out.append(buf, n);
  const int status = pclose(pipe);
  run.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  FILE* err = std::fopen(err_file.c_str(), "r");
  if (err) {
    while ((n = fread(buf, 1, sizeof(buf), err)) > 0) run.err.append(buf, n);
    std::fclose(err);
  }
  return run;
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) out.push_back(line);
  return out;
}

std::string freshDir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("cb_paint_" + name + "_" + std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

// Checks the pair of files: sizes, a cloud in front of the sky, PNG = quantised EXR.
void expectCloudImages(const std::string& png_path, const std::string& exr_path, int w, int h) {
  const ImageRgba8 png = readPng(png_path);
  ASSERT_EQ(png.width, w);
  ASSERT_EQ(png.height, h);
  Imf::RgbaInputFile exr(exr_path.c_str());
  const Imath::Box2i window = exr.dataWindow();
  ASSERT_EQ(window.max.x - window.min.x + 1, w);
  ASSERT_EQ(window.max.y - window.min.y + 1, h);
  Imf::Array2D<Imf::Rgba> pixels(h, w);
  exr.setFrameBuffer(&pixels[0][0] - window.min.x - window.min.y * w, 1, size_t(w));
  exr.readPixels(window.min.y, window.max.y);

  // The sky is the corner colour; the cloud is the brighter, whiter middle.
  const uint8_t* sky = png.at(0, 0);
  const uint8_t* centre = png.at(w / 2, h / 2);
  EXPECT_GT(int(centre[0]), int(sky[0]) + 40) << "no bright cloud in the middle of the image";
  EXPECT_EQ(int(png.at(w - 1, h - 1)[2]), int(sky[2])) << "corners should both be sky";
  long cloud_pixels = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) cloud_pixels += std::abs(int(png.at(x, y)[0]) - int(sky[0])) > 30;
  const double coverage = double(cloud_pixels) / (double(w) * h);
  EXPECT_GT(coverage, 0.05);
  EXPECT_LT(coverage, 0.8);

  // Same render: the PNG is the EXR quantised (±1 for rounding).
  for (int y = 0; y < h; y += 7) {
    for (int x = 0; x < w; x += 5) {
      const Imf::Rgba& f = pixels[y][x];
      const float rgb[3] = {float(f.r), float(f.g), float(f.b)};
      for (int c = 0; c < 3; ++c) {
        const int expect = int(std::lround(std::clamp(rgb[c], 0.0f, 1.0f) * 255.0f));
        ASSERT_NEAR(int(png.at(x, y)[c]), expect, 1) << "pixel " << x << "," << y << " c" << c;
      }
    }
  }
}

TEST(PaintHeadless, DefaultRunWritesPngAndExrAndPrintsTheirPaths) {
  const std::string dir = freshDir("default");
  const ProcessResult run = runCloudbrush(dir, "");
  ASSERT_EQ(run.status, 0) << run.err;
  const std::vector<std::string> paths = lines(run.out);
  ASSERT_EQ(paths.size(), 2u) << "stdout:\n" << run.out;
  EXPECT_EQ(paths[0], "out/cloudbrush-cumulus.png");
  EXPECT_EQ(paths[1], "out/cloudbrush-cumulus.exr");
  EXPECT_NE(run.err.find("surfaceless"), std::string::npos) << run.err;
  expectCloudImages(dir + "/" + paths[0], dir + "/" + paths[1], 1280, 720);
  std::filesystem::remove_all(dir);
}

TEST(PaintHeadless, SizeGridAndOutDirAreHonoured) {
  const std::string dir = freshDir("small");
  const ProcessResult run = runCloudbrush(
      dir, "paint --display surfaceless --size 200x120 --grid 64 --out-dir renders/a");
  ASSERT_EQ(run.status, 0) << run.err;
  const std::vector<std::string> paths = lines(run.out);
  ASSERT_EQ(paths.size(), 2u) << run.out;
  EXPECT_EQ(paths[0], "renders/a/cloudbrush-cumulus.png");
  expectCloudImages(dir + "/" + paths[0], dir + "/" + paths[1], 200, 120);
  std::filesystem::remove_all(dir);
}

TEST(PaintHeadless, BadOptionsFailClearlyWithoutOutput) {
  const std::string dir = freshDir("bad");
  struct Case {
    const char* args;
    const char* names;
  };
  for (const Case& c :
       {Case{"--display wayland", "--display"}, Case{"--size 0x5", "--size"},
        Case{"--size 640", "--size"}, Case{"--grid 3", "--grid"},
        Case{"--frobnicate 1", "--frobnicate"},
        Case{"--display kms --drm-device /nonexistent/card9", "/nonexistent/card9"}}) {
    const ProcessResult run = runCloudbrush(dir, c.args);
    EXPECT_NE(run.status, 0) << c.args;
    EXPECT_TRUE(run.out.empty()) << c.args << ": " << run.out;
    EXPECT_NE(run.err.find(c.names), std::string::npos) << c.args << ": " << run.err;
  }
  EXPECT_FALSE(std::filesystem::exists(dir + "/out"));
  std::filesystem::remove_all(dir);
}

// A driver without OpenGL 4.5 core (llvmpipe told to offer 3.3): say what was found and what is
// needed, exit non-zero, write nothing.
TEST(PaintHeadless, TooOldOpenGlNamesFoundAndNeededVersions) {
  const std::string dir = freshDir("oldgl");
  const ProcessResult run = runCloudbrush(dir, "", "MESA_GL_VERSION_OVERRIDE=3.3");
  EXPECT_NE(run.status, 0);
  EXPECT_TRUE(run.out.empty()) << run.out;
  EXPECT_NE(run.err.find("OpenGL 4.5 core profile is needed"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("offers OpenGL 3.3"), std::string::npos) << run.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/out"));
  std::filesystem::remove_all(dir);
}

TEST(PaintHeadless, HelpDescribesTheDisplayFlag) {
  const std::string dir = freshDir("help");
  const ProcessResult run = runCloudbrush(dir, "paint --help");
  EXPECT_EQ(run.status, 0);
  EXPECT_NE(run.out.find("--display auto|kms|x11|surfaceless"), std::string::npos) << run.out;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace cb
