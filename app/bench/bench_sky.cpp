// `cloudbrush bench sky`: what the sparse volume (issue 15, "A sky without walls") costs as the
// sky grows. For skies of 1×, 4× and 16× today's area at today's voxel size (256×256×256,
// 512×256×512, 1024×256×1024 voxels, 2/256 world units each): the bytes an empty sky holds
// (Volume::memoryBytes: the brick table, no bricks), the bytes with the bundled 256³ cumulus
// placed at its centre, the time to place it (row by row, writeLine) and to read the whole sky
// row by row (as the checksum and the volume file do), with the process RSS beside. Baseline in
// the same run: the dense grid the sky would be (its bytes, and the same cumulus copied into a
// dense std::vector for the 1× sky). CPU volume only: the light volume and the GL textures are
// still dense over the sky's extent (stage 2 of the issue), so they are not counted here.
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "app/bench/bench_report.h"
#include "app/bench/benches.h"
#include "app/volume/scene_generators.h"
#include "app/volume/volume.h"

namespace cb {
namespace {

using Clock = std::chrono::steady_clock;

double rssMb() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("VmRSS:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;
  return -1.0;
}

volatile double g_keep;  // keeps the read loop from being optimised away

double mb(size_t bytes) {
  return double(bytes) / double(1 << 20);
}

}  // namespace

int benchSky(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--help") == 0) {
      std::printf(
          "usage: cloudbrush bench sky\n"
          "  bytes of an empty sky and of the bundled cumulus in it, for 1x, 4x and 16x\n"
          "  today's area, against the dense grid's bytes (CPU volume only)\n");
      return 0;
    }
    std::fprintf(stderr, "bench sky: unknown option '%s'\n", argv[i]);
    return 2;
  }
  BenchReport report("sky");
  const Volume cumulus = makeBundledCumulus(glm::ivec3(256));
  const glm::ivec3 cd = cumulus.dims();
  std::printf("bench sky: the bundled cumulus %dx%dx%d (%zu bricks, %.1f MiB sparse)\n", cd.x, cd.y,
              cd.z, cumulus.allocatedBricks(), mb(cumulus.memoryBytes()));
  std::vector<float> row(size_t(cd.x));

  // Baseline: the dense path for today's box, the cumulus copied into a dense grid.
  {
    const auto t0 = Clock::now();
    std::vector<float> dense(cumulus.voxelCount(), 0.0f);
    for (int z = 0; z < cd.z; ++z)
      for (int y = 0; y < cd.y; ++y)
        cumulus.readLine({0, y, z}, 0, cd.x, &dense[cumulus.index(0, y, z)]);
    const double ms = msSince(t0);
    std::printf("dense baseline 1x: %.1f MiB, cumulus placed in %.1f ms\n",
                mb(dense.size() * sizeof(float)), ms);
    report.baseline("1x_place_cumulus_ms", ms);
  }

  std::printf("\n%-5s %-16s | %10s | %12s %7s | %9s | %9s | %8s | %s\n", "sky", "voxels",
              "empty MiB", "cumulus MiB", "bricks", "place ms", "read ms", "RSS MiB",
              "dense MiB (baseline)");
  for (const int area : {1, 4, 16}) {
    const int side = area == 1 ? 256 : area == 4 ? 512 : 1024;
    const glm::ivec3 dims(side, 256, side);
    const glm::vec3 half = glm::vec3(dims) / 256.0f;  // 2/256 world units per voxel, as today
    Volume sky(dims, -half, half);
    const size_t empty = sky.memoryBytes();
    const glm::ivec3 offset = (dims - cd) / 2;
    auto t0 = Clock::now();
    for (int z = 0; z < cd.z; ++z)
      for (int y = 0; y < cd.y; ++y) {
        cumulus.readLine({0, y, z}, 0, cd.x, row.data());
        sky.writeLine(offset + glm::ivec3(0, y, z), 0, cd.x, row.data());
      }
    sky.markDirty({offset, offset + cd});
    const double place_ms = msSince(t0);
    t0 = Clock::now();
    std::vector<float> line(size_t(dims.x));
    double sum = 0.0;
    for (int z = 0; z < dims.z; ++z)
      for (int y = 0; y < dims.y; ++y) {
        sky.readLine({0, y, z}, 0, dims.x, line.data());
        sum += line[size_t(dims.x / 2)];
      }
    const double read_ms = msSince(t0);
    g_keep = sum;
    const double rss = rssMb();
    const size_t dense = sky.voxelCount() * sizeof(float);
    const std::string name = std::to_string(area) + "x";
    const std::string voxels =
        std::to_string(dims.x) + "x" + std::to_string(dims.y) + "x" + std::to_string(dims.z);
    std::printf("%-5s %-16s | %10.2f | %12.1f %7zu | %9.1f | %9.1f | %8.1f | %.0f\n", name.c_str(),
                voxels.c_str(), mb(empty), mb(sky.memoryBytes()), sky.allocatedBricks(), place_ms,
                read_ms, rss, mb(dense));
    report.figure(name + "_empty_bytes", double(empty));
    report.figure(name + "_cumulus_bytes", double(sky.memoryBytes()));
    report.figure(name + "_cumulus_bricks", double(sky.allocatedBricks()));
    report.figure(name + "_place_cumulus_ms", place_ms);
    report.figure(name + "_read_all_ms", read_ms);
    report.figure(name + "_rss_mb", rss);
    report.baseline(name + "_dense_bytes", double(dense));
  }
  std::printf(
      "\nempty sky <= 50 MB (CPU bricks only; light bricks and the brick pool are stage 2): "
      "see the 16x row\n"
      "cumulus + 100 strokes across the sky <= 1 GB: not measured (needs the canvas across the "
      "sky, stage 3)\n");
  report.note("not_counted", "light volume and GL textures (still dense, stage 2)");
  report.print();
  return 0;
}

}  // namespace cb
