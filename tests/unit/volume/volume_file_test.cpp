#include "app/volume/volume_file.h"

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "app/volume/scene_generators.h"

namespace cb {
namespace {

std::string tempPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() /
          ("cb_volume_file_test_" + std::to_string(::getpid()) + "_" + name))
      .string();
}

std::string errorOf(const std::string& path) {
  try {
    loadVolume(path);
  } catch (const VolumeFileError& e) {
    return e.what();
  }
  return "";
}

void writeBytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

std::string readBytes(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), {});
}

TEST(VolumeFile, RoundTripKeepsDimsWorldBoxAndEveryByte) {
  Volume v = makeSphere({12, 8, 6}, glm::vec3(0.1f), 0.7f);
  Volume w({12, 8, 6}, glm::vec3(-2, 0, -1), glm::vec3(2, 1.5f, 1));
  w.assignDense(v.toDense().data());
  std::string p = tempPath("roundtrip.cbvol");
  saveVolume(w, p);
  Volume r = loadVolume(p);
  EXPECT_EQ(r.dims(), w.dims());
  EXPECT_EQ(r.worldMin(), w.worldMin());
  EXPECT_EQ(r.worldMax(), w.worldMax());
  EXPECT_EQ(std::memcmp(r.toDense().data(), w.toDense().data(), w.voxelCount() * 4), 0);
  std::filesystem::remove(p);
}

TEST(VolumeFile, BadFilesGiveErrorsNamingTheFileAndTheProblem) {
  Volume v = makeSingleVoxel({4, 4, 4}, {1, 1, 1});
  std::string good = tempPath("good.cbvol");
  saveVolume(v, good);
  std::string bytes = readBytes(good);
  size_t header_end = bytes.find('\n') + 1;

  std::string missing = tempPath("does_not_exist.cbvol");
  EXPECT_NE(errorOf(missing).find(missing), std::string::npos);
  EXPECT_NE(errorOf(missing).find("cannot open"), std::string::npos);

  std::string p = tempPath("bad.cbvol");
  writeBytes(p, bytes.substr(0, bytes.size() - 10));
  EXPECT_NE(errorOf(p).find(p), std::string::npos);
  EXPECT_NE(errorOf(p).find("truncated"), std::string::npos) << errorOf(p);

  writeBytes(p, bytes + "xxxx");
  EXPECT_NE(errorOf(p).find("trailing data"), std::string::npos) << errorOf(p);

  std::string header = bytes.substr(0, header_end);
  std::string body = bytes.substr(header_end);
  auto replaced = [&](const std::string& from, const std::string& to) {
    std::string h = header;
    h.replace(h.find(from), from.size(), to);
    return h + body;
  };
  writeBytes(p, replaced("[4,4,4]", "[4,4,5]"));
  EXPECT_NE(errorOf(p).find("truncated"), std::string::npos) << errorOf(p);
  writeBytes(p, replaced("[4,4,4]", "[4,4,3]"));
  EXPECT_NE(errorOf(p).find("trailing data"), std::string::npos) << errorOf(p);
  writeBytes(p, replaced("[4,4,4]", "[4,0,4]"));
  EXPECT_NE(errorOf(p).find("dims"), std::string::npos) << errorOf(p);
  writeBytes(p, replaced("\"version\":1", "\"version\":9"));
  EXPECT_NE(errorOf(p).find("version"), std::string::npos) << errorOf(p);
  writeBytes(p, replaced("float32", "float64"));
  EXPECT_NE(errorOf(p).find("float64"), std::string::npos) << errorOf(p);
  writeBytes(p, replaced("\"dims\"", "\"dimz\""));
  EXPECT_NE(errorOf(p).find("header field 'dims' is missing"), std::string::npos) << errorOf(p);
  writeBytes(p, std::string("P6\n4 4\n255\n") + std::string(48, '\0'));
  EXPECT_NE(errorOf(p).find("malformed JSON"), std::string::npos) << errorOf(p);
  writeBytes(p, "");
  EXPECT_NE(errorOf(p).find("no header line"), std::string::npos) << errorOf(p);
  std::string nan_body = body;
  float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(nan_body.data() + 8, &nan, 4);
  writeBytes(p, header + nan_body);
  EXPECT_NE(errorOf(p).find("non-finite density at voxel index 2"), std::string::npos)
      << errorOf(p);
  std::filesystem::remove(p);
  std::filesystem::remove(good);
}

}  // namespace
}  // namespace cb
