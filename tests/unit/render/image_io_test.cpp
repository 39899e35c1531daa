#include "app/render/image_io.h"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

namespace cb {
namespace {

std::string tempPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() /
          ("cb_image_io_test_" + std::to_string(::getpid()) + "_" + name))
      .string();
}

TEST(ImageIo, PngRoundTripIsExactAndRowZeroIsTheTop) {
  ImageRgba8 img;
  img.width = 5;
  img.height = 3;
  img.pixels.resize(5 * 3 * 4);
  for (size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = uint8_t(i * 7 + 3);
  std::string p = tempPath("a.png");
  writePng(p, img);
  ImageRgba8 back = readPng(p);
  EXPECT_EQ(back.width, 5);
  EXPECT_EQ(back.height, 3);
  EXPECT_EQ(back.pixels, img.pixels);
  std::filesystem::remove(p);
}

TEST(ImageIo, ExrIsWrittenWithItsMagicNumber) {
  ImageRgbaF img;
  img.width = 4;
  img.height = 2;
  img.pixels.assign(4 * 2 * 4, 0.5f);
  std::string p = tempPath("a.exr");
  writeExr(p, img);
  std::ifstream f(p, std::ios::binary);
  unsigned char magic[4] = {};
  f.read(reinterpret_cast<char*>(magic), 4);
  EXPECT_EQ(magic[0], 0x76);
  EXPECT_EQ(magic[1], 0x2f);
  EXPECT_EQ(magic[2], 0x31);
  EXPECT_EQ(magic[3], 0x01);
  std::filesystem::remove(p);
}

TEST(ImageIo, ErrorsNameTheFile) {
  ImageRgba8 img;
  img.width = 1;
  img.height = 1;
  img.pixels.assign(4, 0);
  try {
    writePng("/nonexistent_dir/x.png", img);
    FAIL() << "no error";
  } catch (const ImageIoError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent_dir/x.png"), std::string::npos);
  }
  try {
    writeImageByExtension(tempPath("x.jpg"), img, {});
    FAIL() << "no error";
  } catch (const ImageIoError& e) {
    EXPECT_NE(std::string(e.what()).find(".png or .exr"), std::string::npos);
  }
  EXPECT_THROW(readPng(tempPath("missing.png")), ImageIoError);
}

}  // namespace
}  // namespace cb
