#include "app/render/image_io.h"

#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

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

// CRC-32 of PNG chunks (ISO 3309, as in the PNG specification's Annex D).
uint32_t pngCrc(const unsigned char* data, size_t n) {
  uint32_t c = 0xffffffffu;
  for (size_t i = 0; i < n; ++i) {
    c ^= data[i];
    for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xedb88320u ^ (c >> 1) : c >> 1;
  }
  return c ^ 0xffffffffu;
}

TEST(ImageIo, PngWhoseHeaderClaimsHugeSizeIsRefusedBeforeAllocating) {
  // A valid small PNG whose IHDR is rewritten to claim 100000 x 100000 pixels (40 GB as RGBA).
  ImageRgba8 img;
  img.width = 2;
  img.height = 2;
  img.pixels.assign(2 * 2 * 4, 200);
  const std::string p = tempPath("huge.png");
  writePng(p, img);
  std::vector<unsigned char> bytes;
  {
    std::ifstream f(p, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(f), {});
  }
  ASSERT_GT(bytes.size(), 33u);
  // Signature (8) + length (4) + "IHDR" (4) + width (4) + height (4) ... CRC after 13 data bytes.
  for (int field = 0; field < 2; ++field) {
    const uint32_t v = 100000;
    for (int b = 0; b < 4; ++b) bytes[16 + field * 4 + b] = (v >> (24 - 8 * b)) & 0xff;
  }
  const uint32_t crc = pngCrc(&bytes[12], 4 + 13);
  for (int b = 0; b < 4; ++b) bytes[29 + b] = (crc >> (24 - 8 * b)) & 0xff;
  {
    std::ofstream f(p, std::ios::binary | std::ios::trunc);
    f.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  }
  try {
    readPng(p);
    FAIL() << "a 100000x100000 PNG was read";
  } catch (const ImageIoError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(p), std::string::npos) << what;
    EXPECT_NE(what.find("IHDR"), std::string::npos) << what;
    EXPECT_NE(what.find("100000x100000"), std::string::npos) << what;
  }
  std::filesystem::remove(p);
}

}  // namespace
}  // namespace cb
