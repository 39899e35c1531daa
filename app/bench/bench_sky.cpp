// `cloudbrush bench sky`: what the sparse volume ("A sky without walls") costs as the
// sky grows. For skies of 1×, 4× and 16× today's area at today's voxel size (256×256×256,
// 512×256×512, 1024×256×1024 voxels, 2/256 world units each): the bytes an empty sky holds
// (Volume::memoryBytes: the brick table, no bricks), the bytes with the bundled 256³ cumulus
// placed at its centre, the time to place it (row by row, writeLine) and to read the whole sky
// row by row (as the checksum and the volume file do), with the process RSS beside. Baseline in
// the same run: the dense grid the sky would be (its bytes, and the same cumulus copied into a
// dense std::vector for the 1× sky).
//
// Then the light volume (light_volume.h, sparse since stage 2): its bytes and the time of a full
// sweep (a light change) for an empty 1024×256×1024 sky, the cumulus in its own 256³ box (the
// baseline: what the light costs today's box), the cumulus in the middle of the large sky, and
// the cumulus plus 100 stroke-sized balls spread across the sky, each for the default sun and a
// low one; and the incremental sweep after one stroke. Baseline beside it: the bytes the dense
// light volume (T and the passed-on values, 8 bytes a voxel) would hold. The GL brick pool is
// counted by its own owner, not here.
//
// Last, the sky growing with what is painted (sky_extent.h): the default sky holding the
// cumulus grown to the widest one by moving bricks, against copying them (the baseline); the
// widest sky's bytes empty; the light's full sweep of the grown sky.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "app/bench/bench_report.h"
#include "app/bench/benches.h"
#include "app/core/parallel_for.h"
#include "app/render/light_volume.h"
#include "app/volume/scene_generators.h"
#include "app/volume/sky_extent.h"
#include "app/volume/volume.h"
#include "app/volume/volume_paste.h"

namespace cb {
namespace {

using Clock = std::chrono::steady_clock;

volatile double g_keep;  // keeps the read loop from being optimised away

// A stroke: balls along a curve of `length` voxels starting at `from`.
void paintStroke(Volume* v, glm::vec3 from, glm::vec3 along, float length, float radius) {
  for (float t = 0.0f; t <= length; t += radius * 0.5f)
    mergeSoftBall(v, from + along * t + glm::vec3(0.0f, 4.0f * std::sin(t * 0.05f), 0.0f), radius);
}

struct LightFigures {
  double ms = 0.0;      // full sweep, median of 3 (wall)
  double cpu_ms = 0.0;  // the same in process CPU (all threads)
  size_t bytes = 0;     // LightVolume::memoryBytes
  size_t bricks = 0;    // lit + through bricks
};

LightFigures fullSweep(const Volume& v, const Light& light) {
  LightFigures out;
  std::vector<double> times, cpu;
  LightVolume lv;
  for (int i = 0; i < 3; ++i) {
    lv = LightVolume{};
    const double c0 = processCpuMs();
    const auto t0 = Clock::now();
    sweepLightVolume(lv, v, light, v.bounds());
    times.push_back(msSince(t0));
    cpu.push_back(processCpuMs() - c0);
  }
  out.ms = median(times);
  out.cpu_ms = median(cpu);
  out.bytes = lv.memoryBytes();
  out.bricks = lv.lit.allocated() + lv.through.allocated();
  return out;
}

void lightFigures(const Volume& cumulus, BenchReport* report) {
  const glm::ivec3 big(1024, 256, 1024);
  const glm::vec3 half = glm::vec3(big) / 256.0f;
  Volume empty(big, -half, half);
  Volume with_cumulus(big, -half, half);
  const glm::ivec3 offset = (big - cumulus.dims()) / 2;
  std::vector<float> row(size_t(cumulus.dims().x));
  for (int z = 0; z < cumulus.dims().z; ++z)
    for (int y = 0; y < cumulus.dims().y; ++y) {
      cumulus.readLine({0, y, z}, 0, cumulus.dims().x, row.data());
      with_cumulus.writeLine(offset + glm::ivec3(0, y, z), 0, cumulus.dims().x, row.data());
    }
  with_cumulus.markDirty({offset, offset + cumulus.dims()});
  // 100 strokes spread over the sky (a fixed sequence: the figures repeat run to run).
  Volume with_strokes = with_cumulus;
  uint32_t state = 12345u;
  auto next = [&] {
    state = state * 1664525u + 1013904223u;
    return float(state >> 8) / float(1u << 24);
  };
  for (int i = 0; i < 100; ++i) {
    const glm::vec3 from(40.0f + next() * 900.0f, 40.0f + next() * 170.0f, 40.0f + next() * 900.0f);
    const float angle = next() * 6.2831853f;
    paintStroke(&with_strokes, from, glm::vec3(std::cos(angle), 0.0f, std::sin(angle)),
                20.0f + next() * 40.0f, 5.0f + next() * 5.0f);
  }

  struct Sun {
    const char* name;
    glm::vec3 direction;
  };
  const Sun suns[] = {{"default", Light{}.direction},
                      {"low", glm::normalize(glm::vec3(-6.0f, 1.0f, 0.3f))}};
  struct Scene {
    const char* name;
    const Volume* volume;
  };
  const Scene scenes[] = {{"empty_sky", &empty},
                          {"cumulus_256", &cumulus},
                          {"cumulus_in_sky", &with_cumulus},
                          {"cumulus_100_strokes_in_sky", &with_strokes}};
  std::printf("\nlight volume (full sweep = a light change; %d threads):\n", workerThreads());
  std::printf("%-27s %-8s | %9s %9s | %9s %7s | %10s | %11s\n", "scene", "sun", "sweep ms",
              "CPU ms", "light MiB", "bricks", "volume MiB", "dense MiB (baseline)");
  for (const Sun& sun : suns)
    for (const Scene& scene : scenes) {
      Light light;
      light.direction = sun.direction;
      const LightFigures f = fullSweep(*scene.volume, light);
      const double dense = double(scene.volume->voxelCount()) * 8.0;
      std::printf("%-27s %-8s | %9.1f %9.1f | %9.2f %7zu | %10.1f | %11.0f\n", scene.name, sun.name,
                  f.ms, f.cpu_ms, mb(f.bytes), f.bricks, mb(scene.volume->memoryBytes()),
                  dense / double(1 << 20));
      const std::string key = std::string("light_") + scene.name + "_" + sun.name;
      report->figure(key + "_sweep_ms", f.ms);
      report->figure(key + "_sweep_cpu_ms", f.cpu_ms);
      // Today's box is the baseline the large sky is held to ("about what it costs in 256³").
      if (scene.volume == &cumulus) report->baseline(key + "_sweep_cpu_ms", f.cpu_ms);
      report->figure(key + "_bytes", double(f.bytes));
      report->baseline(key + "_dense_bytes", dense);
      if (std::string(sun.name) == "default")
        report->figure(std::string(scene.name) + "_cpu_volume_bytes",
                       double(scene.volume->memoryBytes()));
    }

  // One more stroke in the sky with the cumulus and the strokes: the incremental sweep.
  Light light;
  LightVolume lv;
  sweepLightVolume(lv, with_strokes, light, with_strokes.bounds());
  std::vector<double> times;
  Volume painted = with_strokes;
  for (int i = 0; i < 5; ++i) {
    const uint64_t seen = painted.generation();
    paintStroke(&painted, glm::vec3(300.0f + 60.0f * float(i), 150.0f, 700.0f),
                glm::vec3(1.0f, 0.0f, 0.3f), 50.0f, 8.0f);
    const VoxelBox dirty = painted.dirtySince(seen);
    const auto t0 = Clock::now();
    sweepLightVolume(lv, painted, light, dirty);
    times.push_back(msSince(t0));
  }
  const double stroke_ms = median(times);
  const double full_ms = fullSweep(painted, light).ms;
  std::printf(
      "one stroke (50 voxels long, radius 8), incremental sweep: %.1f ms (median of 5); "
      "full sweep of the same sky %.1f ms (baseline)\n",
      stroke_ms, full_ms);
  report->figure("light_one_stroke_incremental_ms", stroke_ms);
  report->baseline("light_one_stroke_full_sweep_ms", full_ms);
  report->figure("rss_mb_after_light", processRssMb());
}

// The sky growing (sky_extent.h growSky): the default sky with the cumulus grown to the widest
// one (2048×256×2048 for grid 256) by moving its bricks, against copying them into the wider
// sky (pasteVolume, the baseline); what the widest sky costs empty, and the light volume's full
// sweep of the grown sky with the cumulus (what the renderer's fresh sync recomputes on the CPU
// at the pen-up of the stroke that grows the sky).
void growthFigures(const Volume& cumulus, BenchReport* report) {
  const SkyExtent from{cumulus.dims().x, kDefaultSkySpan};
  const SkyExtent to{from.grid, widestSkySpan(from.grid, from.span, kMaxSkySpan)};
  const Volume placed = placeInSky(cumulus, from);
  std::vector<double> move_ms, copy_ms;
  size_t grown_bytes = 0;
  for (int i = 0; i < 5; ++i) {
    Volume sky = placed;
    auto t0 = Clock::now();
    const Volume grown = growSky(std::move(sky), from, to);
    move_ms.push_back(msSince(t0));
    grown_bytes = grown.memoryBytes();
    t0 = Clock::now();
    Volume copied = makeSkyVolume(to);
    pasteVolume(placed, placed.bounds(), growthOffset(from, to), &copied);
    copy_ms.push_back(msSince(t0));
  }
  const Volume empty_widest = makeSkyVolume(to);
  const LightFigures empty_light = fullSweep(empty_widest, Light{});
  Volume grown = growSky(Volume(placed), from, to);
  const LightFigures grown_light = fullSweep(grown, Light{});
  const glm::ivec3 d = to.dims();
  std::printf(
      "\nthe sky growing from span %d to %d (%dx%dx%d) around the cumulus: bricks moved in %.2f "
      "ms (median of 5; copying them, the baseline: %.1f ms); the grown sky holds %.1f MiB\n"
      "the widest sky empty: volume %.2f MiB + light %.2f MiB; the light's full sweep of the "
      "grown sky with the cumulus: %.1f ms wall, %.1f ms CPU, %.1f MiB\n",
      from.span, to.span, d.x, d.y, d.z, median(move_ms), median(copy_ms), mb(grown_bytes),
      mb(empty_widest.memoryBytes()), mb(empty_light.bytes), grown_light.ms, grown_light.cpu_ms,
      mb(grown_light.bytes));
  report->figure("grow_sky_move_ms", median(move_ms));
  report->baseline("grow_sky_copy_ms", median(copy_ms));
  report->figure("widest_sky_empty_bytes", double(empty_widest.memoryBytes()));
  report->figure("widest_sky_empty_light_bytes", double(empty_light.bytes));
  report->figure("grown_sky_cumulus_light_sweep_ms", grown_light.ms);
}

}  // namespace

int benchSky(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--help") == 0) {
      std::printf(
          "usage: cloudbrush bench sky\n"
          "  bytes of an empty sky and of the bundled cumulus in it, for 1x, 4x and 16x\n"
          "  today's area, against the dense grid's bytes (CPU volume); the light volume's\n"
          "  bytes and sweep times for an empty sky, the cumulus and 100 strokes; the sky\n"
          "  growing around the cumulus to its widest\n");
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
    const double rss = processRssMb();
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
  lightFigures(cumulus, &report);
  growthFigures(cumulus, &report);
  std::printf(
      "\nempty sky <= 50 MB: CPU bricks (16x row) + light (empty_sky rows) + the GL brick pool "
      "(counted by the renderer)\n"
      "cumulus + 100 strokes across the sky <= 1 GB: CPU volume + light in the "
      "cumulus_100_strokes_in_sky rows (+ the GL brick pool)\n");
  report.note("not_counted", "the GL brick pool (the renderer's own figures)");
  report.print();
  return 0;
}

}  // namespace cb
