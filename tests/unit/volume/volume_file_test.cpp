#include "app/volume/volume_file.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

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

// The same voxels, bit for bit: dims, world box, which bricks exist and every brick's bytes.
void expectIdentical(const Volume& a, const Volume& b) {
  ASSERT_EQ(a.dims(), b.dims());
  EXPECT_EQ(a.worldMin(), b.worldMin());
  EXPECT_EQ(a.worldMax(), b.worldMax());
  const std::vector<glm::ivec3> bricks = a.allocatedBrickList();
  ASSERT_EQ(bricks, b.allocatedBrickList());
  size_t differing = 0;
  for (const glm::ivec3 brick : bricks)
    differing += std::memcmp(a.brick(brick), b.brick(brick), Volume::kBrickBytes) != 0;
  EXPECT_EQ(differing, 0u) << "of " << bricks.size() << " bricks";
}

// The header line of the file at `path` and the bytes after it.
std::pair<std::string, std::string> splitFile(const std::string& path) {
  const std::string bytes = readBytes(path);
  const size_t end = bytes.find('\n') + 1;
  return {bytes.substr(0, end), bytes.substr(end)};
}

// `volume` as a version 1 file (the whole grid, dense), as versions before the stored box wrote.
std::string versionOneFile(const Volume& volume) {
  const glm::ivec3 d = volume.dims();
  char world[256];
  std::snprintf(
      world, sizeof world, "\"world_min\":[%.9g,%.9g,%.9g],\"world_max\":[%.9g,%.9g,%.9g]",
      double(volume.worldMin().x), double(volume.worldMin().y), double(volume.worldMin().z),
      double(volume.worldMax().x), double(volume.worldMax().y), double(volume.worldMax().z));
  std::string out = "{\"format\":\"cloudbrush-volume\",\"version\":1,\"dims\":[" +
                    std::to_string(d.x) + "," + std::to_string(d.y) + "," + std::to_string(d.z) +
                    "]," + world +
                    ",\"type\":\"float32\",\"endian\":\"little\",\"order\":" + "\"x-fastest\"}\n";
  const std::vector<float> dense = volume.toDense();
  out.append(reinterpret_cast<const char*>(dense.data()), dense.size() * sizeof(float));
  return out;
}

TEST(VolumeFile, ACumulusInTheMiddleOfABigSkyIsAFileOfTheCumulusBoxSize) {
  // The bundled cumulus (256³ over [-1,1]³) placed in the middle of a 1024×256×1024 sky over
  // [-4,4]×[-1,1]×[-4,4] (the same voxel size): voxels x 384..639, z 384..639.
  const Volume cumulus = makeBundledCumulus();
  const glm::ivec3 offset(384, 0, 384);
  Volume sky({1024, 256, 1024}, {-4, -1, -4}, {4, 1, 4});
  std::vector<float> row(256);
  for (int z = 0; z < 256; ++z)
    for (int y = 0; y < 256; ++y) {
      cumulus.readLine({0, y, z}, 0, 256, row.data());
      sky.writeLine(offset + glm::ivec3(0, y, z), 0, 256, row.data());
    }
  sky.markDirty(sky.bounds());

  // The cumulus's non-zero box, found here from its dense copy.
  const std::vector<float> dense = cumulus.toDense();
  VoxelBox expected;
  for (int z = 0; z < 256; ++z)
    for (int y = 0; y < 256; ++y)
      for (int x = 0; x < 256; ++x)
        if (dense[cumulus.index(x, y, z)] != 0.0f)
          expected = expected.unite({{x, y, z}, {x + 1, y + 1, z + 1}});
  ASSERT_FALSE(expected.empty());
  expected = {expected.lo + offset, expected.hi + offset};

  const std::string path = tempPath("sky_cumulus.cbvol");
  saveVolume(sky, path);
  const auto [header, body] = splitFile(path);
  const std::string box = "\"stored_min\":[" + std::to_string(expected.lo.x) + "," +
                          std::to_string(expected.lo.y) + "," + std::to_string(expected.lo.z) +
                          "],\"stored_max\":[" + std::to_string(expected.hi.x) + "," +
                          std::to_string(expected.hi.y) + "," + std::to_string(expected.hi.z) + "]";
  EXPECT_NE(header.find("\"version\":2"), std::string::npos) << header;
  EXPECT_NE(header.find("\"dims\":[1024,256,1024]"), std::string::npos) << header;
  EXPECT_NE(header.find(box), std::string::npos) << header << "expected " << box;
  EXPECT_EQ(body.size(), size_t(expected.voxelCount()) * sizeof(float));
  const uint64_t file_bytes = std::filesystem::file_size(path);
  const uint64_t dense_sky_bytes = uint64_t(sky.voxelCount()) * sizeof(float);
  std::printf(
      "cumulus in a 1024x256x1024 sky: stored box %dx%dx%d, file %llu bytes; the whole "
      "grid would be %llu bytes (%.1fx), the cumulus's 256^3 grid %llu bytes\n",
      expected.hi.x - expected.lo.x, expected.hi.y - expected.lo.y, expected.hi.z - expected.lo.z,
      (unsigned long long)file_bytes, (unsigned long long)dense_sky_bytes,
      double(dense_sky_bytes) / double(file_bytes),
      (unsigned long long)(cumulus.voxelCount() * sizeof(float)));
  EXPECT_LE(file_bytes, cumulus.voxelCount() * sizeof(float) + header.size());

  const Volume loaded = loadVolume(path);
  expectIdentical(sky, loaded);
  std::filesystem::remove(path);
}

TEST(VolumeFile, AnEmptySkyIsTheHeaderAlone) {
  const Volume sky({1024, 256, 1024}, {-4, -1, -4}, {4, 1, 4});
  const std::string path = tempPath("sky_empty.cbvol");
  saveVolume(sky, path);
  const auto [header, body] = splitFile(path);
  EXPECT_TRUE(body.empty()) << body.size() << " bytes after the header";
  EXPECT_NE(header.find("\"stored_min\":[0,0,0],\"stored_max\":[0,0,0]"), std::string::npos)
      << header;
  const Volume loaded = loadVolume(path);
  EXPECT_EQ(loaded.dims(), sky.dims());
  EXPECT_EQ(loaded.allocatedBricks(), 0u);
  expectIdentical(sky, loaded);
  std::filesystem::remove(path);
}

TEST(VolumeFile, NegativeZeroAndEdgeVoxelsAreKept) {
  // -0 is not +0 bit for bit, so it is stored; voxels on the last row and column of a grid
  // whose dims are not a multiple of the brick size bound the box.
  Volume v({37, 21, 19}, glm::vec3(-1), glm::vec3(1));
  v.set(3, 4, 5, -0.0f);
  v.set(36, 20, 18, 0.25f);
  const std::string path = tempPath("edges.cbvol");
  saveVolume(v, path);
  const auto [header, body] = splitFile(path);
  EXPECT_NE(header.find("\"stored_min\":[3,4,5],\"stored_max\":[37,21,19]"), std::string::npos)
      << header;
  const Volume loaded = loadVolume(path);
  expectIdentical(v, loaded);
  EXPECT_TRUE(std::signbit(loaded.at(3, 4, 5)));
  std::filesystem::remove(path);
}

TEST(VolumeFile, VersionOneFilesLoadAsBefore) {
  // A version 1 file holds the whole grid; it loads to the same voxels and the same bricks as
  // the version 2 file of the same volume (replayed journals that opened one see no change).
  Volume v = makeSparsePuffs(glm::ivec3(48, 32, 40), 3);
  v.set(0, 0, 0, -0.0f);
  const std::string v1 = tempPath("v1.cbvol"), v2 = tempPath("v2.cbvol");
  writeBytes(v1, versionOneFile(v));
  saveVolume(v, v2);
  EXPECT_LT(std::filesystem::file_size(v2), std::filesystem::file_size(v1));
  const Volume from_v1 = loadVolume(v1);
  expectIdentical(v, from_v1);
  expectIdentical(from_v1, loadVolume(v2));
  // Through a pipe too.
  std::istringstream in(readBytes(v1));
  expectIdentical(v, readVolume(in, "v1 pipe", std::nullopt));
  std::filesystem::remove(v1);
  std::filesystem::remove(v2);
}

TEST(VolumeFile, BadFilesGiveErrorsNamingTheFileAndTheProblem) {
  Volume v = makeSingleVoxel({4, 4, 4}, {1, 1, 1});
  v.set(2, 3, 2, 0.5f);  // the stored box: [1,1,1]..[3,4,3], 2x3x2 voxels
  std::string good = tempPath("good.cbvol");
  saveVolume(v, good);
  const auto [header, body] = splitFile(good);
  ASSERT_EQ(body.size(), 12u * 4u);
  ASSERT_NE(header.find("\"stored_min\":[1,1,1],\"stored_max\":[3,4,3]"), std::string::npos)
      << header;

  std::string missing = tempPath("does_not_exist.cbvol");
  EXPECT_NE(errorOf(missing).find(missing), std::string::npos);
  EXPECT_NE(errorOf(missing).find("cannot open"), std::string::npos);

  std::string p = tempPath("bad.cbvol");
  writeBytes(p, header + body.substr(0, body.size() - 10));
  EXPECT_NE(errorOf(p).find(p), std::string::npos);
  EXPECT_NE(errorOf(p).find("truncated"), std::string::npos) << errorOf(p);

  writeBytes(p, header + body + "xxxx");
  EXPECT_NE(errorOf(p).find("trailing data"), std::string::npos) << errorOf(p);

  auto replaced = [&](const std::string& from, const std::string& to) {
    std::string h = header;
    h.replace(h.find(from), from.size(), to);
    return h + body;
  };
  const std::string box_bytes = "header fields 'stored_min', 'stored_max': the stored box ";
  writeBytes(p, replaced("\"stored_max\":[3,4,3]", "\"stored_max\":[3,4,4]"));
  EXPECT_NE(errorOf(p).find(box_bytes + "[1,1,1]..[3,4,4] (18 voxels) needs 72 bytes of float32 "
                                        "but the file holds 48 bytes after the header (truncated"),
            std::string::npos)
      << errorOf(p);
  writeBytes(p, replaced("\"stored_min\":[1,1,1]", "\"stored_min\":[1,1,2]"));
  EXPECT_NE(errorOf(p).find(box_bytes + "[1,1,2]..[3,4,3] (6 voxels) needs 24 bytes of float32 "
                                        "but the file holds 48 bytes after the header (trailing"),
            std::string::npos)
      << errorOf(p);
  writeBytes(p, replaced("\"stored_max\":[3,4,3]", "\"stored_max\":[3,5,3]"));
  EXPECT_NE(errorOf(p).find("header field 'stored_max': 5 (y) lies outside dims 4x4x4"),
            std::string::npos)
      << errorOf(p);
  writeBytes(p, replaced("\"dims\":[4,4,4]", "\"dims\":[4,4,2]"));
  EXPECT_NE(errorOf(p).find("header field 'stored_max': 3 (z) lies outside dims 4x4x2"),
            std::string::npos)
      << errorOf(p);
  writeBytes(p, replaced("\"stored_min\":[1,1,1]", "\"stored_min\":[-1,1,1]"));
  EXPECT_NE(errorOf(p).find("header field 'stored_min': -1 (x) is not a non-negative integer"),
            std::string::npos)
      << errorOf(p);
  writeBytes(p, replaced("\"stored_min\":[1,1,1]", "\"stored_min\":[1,1.5,1]"));
  EXPECT_NE(errorOf(p).find("header field 'stored_min': 1.5 (y) is not a non-negative integer"),
            std::string::npos)
      << errorOf(p);
  writeBytes(p, replaced("\"stored_min\":[1,1,1]", "\"stored_min\":[1,1,4]"));
  EXPECT_NE(errorOf(p).find("header field 'stored_max': 3 (z) is below stored_min 4"),
            std::string::npos)
      << errorOf(p);
  writeBytes(p, replaced("\"stored_min\":[1,1,1]", "\"stored_min\":[1,1]"));
  EXPECT_NE(errorOf(p).find("header field 'stored_min' must be an array of 3 non-negative"),
            std::string::npos)
      << errorOf(p);
  writeBytes(p, replaced("\"stored_min\"", "\"stored_mix\""));
  EXPECT_NE(errorOf(p).find("header field 'stored_min' is missing"), std::string::npos)
      << errorOf(p);
  writeBytes(p, replaced("\"version\":2", "\"version\":1"));
  EXPECT_NE(errorOf(p).find("header field 'stored_min' is not part of version 1"),
            std::string::npos)
      << errorOf(p);
  writeBytes(p, replaced("\"dims\":[4,4,4]", "\"dims\":[4,0,4]"));
  EXPECT_NE(errorOf(p).find("header field 'dims'"), std::string::npos) << errorOf(p);
  writeBytes(p, replaced("\"version\":2", "\"version\":9"));
  EXPECT_NE(errorOf(p).find("header field 'version': 9 is unsupported"), std::string::npos)
      << errorOf(p);
  writeBytes(p, replaced("float32", "float64"));
  EXPECT_NE(errorOf(p).find("float64"), std::string::npos) << errorOf(p);
  writeBytes(p, replaced("\"dims\"", "\"dimz\""));
  EXPECT_NE(errorOf(p).find("header field 'dims' is missing"), std::string::npos) << errorOf(p);
  writeBytes(p, std::string("P6\n4 4\n255\n") + std::string(48, '\0'));
  EXPECT_NE(errorOf(p).find("malformed JSON"), std::string::npos) << errorOf(p);
  writeBytes(p, "");
  EXPECT_NE(errorOf(p).find("no header line"), std::string::npos) << errorOf(p);
  // The third stored float is voxel (1,2,1): the box is 2 voxels wide.
  std::string nan_body = body;
  float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(nan_body.data() + 8, &nan, 4);
  writeBytes(p, header + nan_body);
  EXPECT_NE(errorOf(p).find("non-finite density at voxel index 25 (x 1, y 2, z 1)"),
            std::string::npos)
      << errorOf(p);
  std::filesystem::remove(p);
  std::filesystem::remove(good);
}

}  // namespace
}  // namespace cb
