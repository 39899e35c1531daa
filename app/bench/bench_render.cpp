// cloudbrush bench render: the volume renderer on this machine (llvmpipe), 1280×720, the bundled
// cumulus and the sparse puffs at 256³, the reference camera. Figures: frame time with and
// without empty-space skipping, samples per frame, light volume recompute (sweep) next to the
// reference march of Alg. 5, orbit fps at reduced resolution, and Debian's vdb_render on the
// same volume, view and size. Baselines (no-skip frame, reference march, vdb_render) are measured
// in the same run. Prints targets met/missed; never fails on a target.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "app/bench/bench_report.h"
#include "app/bench/benches.h"
#include "app/cli/args.h"
#include "app/core/config_paths.h"
#include "app/core/parallel_for.h"
#include "app/render/gl/egl_context.h"
#include "app/render/light_accuracy.h"
#include "app/render/light_volume.h"
#include "app/render/render_config.h"
#include "app/render/render_target.h"
#include "app/render/volume_renderer.h"
#include "app/volume/scene_generators.h"
#include "app/volume/volume_file.h"

namespace cb {
namespace {

const char kHelp[] =
    "usage: cloudbrush bench render [--size WxH] [--frames N] [--dims N] [--no-vdb]\n"
    "  --size WxH   image size (default 1280x720)\n"
    "  --frames N   timed frames per configuration, median reported (default 5)\n"
    "  --dims N     volume size N³ (default 256)\n"
    "  --no-vdb     skip the vdb_render comparison (it takes ~10 s a scene here)\n";

using Clock = std::chrono::steady_clock;

double loadAverage() {
  double load = -1;
  if (FILE* f = std::fopen("/proc/loadavg", "r")) {
    if (std::fscanf(f, "%lf", &load) != 1) load = -1;
    std::fclose(f);
  }
  return load;
}

void printTarget(const char* what, double value, const char* unit, double bound, bool at_most) {
  bool met = at_most ? value <= bound : value >= bound;
  std::printf("  target %-52s %9.2f %-4s (%s %g) %s\n", what, value, unit,
              at_most ? "<=" : ">=", bound, met ? "MET" : "MISSED");
}

std::string executableDir() {
  std::error_code ec;
  auto p = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::string(".") : p.parent_path().string();
}

// Runs a shell command, returns its exit status and stdout+stderr.
int runCommand(const std::string& cmd, std::string* output) {
  output->clear();
  FILE* p = popen((cmd + " 2>&1").c_str(), "r");
  if (!p) return -1;
  char buf[512];
  while (fgets(buf, sizeof buf, p)) *output += buf;
  return pclose(p);
}

struct SceneResult {
  double frame_skip_ms = 0, frame_noskip_ms = 0;
  uint64_t samples_skip = 0, samples_noskip = 0;
};

const char* const kSceneNames[2] = {"cumulus", "sparse"};

// What every part of the bench shares: the renderer and its target, the sizes, the report.
struct RenderBench {
  RenderBench(VolumeRenderer& r, RenderTarget& t, BenchReport& rep, int w, int h, int f, int dims)
      : renderer(r), target(t), report(rep), width(w), height(h), frames(f), n(dims) {}
  VolumeRenderer& renderer;
  RenderTarget& target;
  BenchReport& report;
  int width, height, frames, n;
  const Camera camera = Camera::reference();
  const Light light;
  double last_frame_cpu_ms = 0;  // process CPU time (llvmpipe's threads included)

  // The median frame time of `frames` finished frames (and their CPU time in last_frame_cpu_ms).
  double frameMs(const Camera& cam, RenderOptions opt) {
    opt.finish = true;
    std::vector<double> t, cpu;
    for (int i = 0; i < frames; ++i) {
      double c0 = processCpuMs();
      renderer.render(cam, width, height, target.fbo(), opt);
      cpu.push_back(processCpuMs() - c0);
      t.push_back(renderer.lastStats().frame_ms);
    }
    last_frame_cpu_ms = median(cpu);
    return median(t);
  }
  RenderStats samples(RenderOptions opt) {
    opt.collect_stats = true;
    renderer.render(camera, width, height, target.fbo(), opt);
    return renderer.lastStats();
  }
};

// One scene: its full sync, and frames with and without empty-space skipping.
SceneResult benchScene(RenderBench& b, const Volume& v, const std::string& p) {
  SyncStats sync = b.renderer.sync(v, b.light);
  std::printf(
      "\n%s: full sync: occupancy %.1f ms, light sweep %.1f ms, pack %.1f ms, upload %.1f ms\n",
      p.c_str(), sync.occupancy_ms, sync.light_ms, sync.pack_ms, sync.upload_ms);
  b.report.figure(p + "_sync_occupancy_ms", sync.occupancy_ms);
  b.report.figure(p + "_sync_light_ms", sync.light_ms);
  b.report.figure(p + "_sync_pack_ms", sync.pack_ms);
  b.report.figure(p + "_sync_upload_ms", sync.upload_ms);
  RenderOptions skip, noskip;
  noskip.skip_empty_space = false;
  // The first frame after a program change pays llvmpipe's shader JIT; report it apart.
  RenderOptions first = skip;
  first.finish = true;
  b.renderer.render(b.camera, b.width, b.height, b.target.fbo(), first);
  double first_ms = b.renderer.lastStats().frame_ms;
  SceneResult r;
  r.frame_skip_ms = b.frameMs(b.camera, skip);
  const double skip_cpu = b.last_frame_cpu_ms;
  r.frame_noskip_ms = b.frameMs(b.camera, noskip);
  const double noskip_cpu = b.last_frame_cpu_ms;
  std::printf("%s: process CPU per frame %.1f ms with skipping, %.1f ms without\n", p.c_str(),
              skip_cpu, noskip_cpu);
  b.report.figure(p + "_frame_cpu_ms", skip_cpu);
  b.report.baseline(p + "_frame_noskip_cpu_ms", noskip_cpu);
  RenderStats st_skip = b.samples(skip), st_noskip = b.samples(noskip);
  r.samples_skip = st_skip.samples_total;
  r.samples_noskip = st_noskip.samples_total;
  std::printf("%s: frame %.1f ms with skipping, %.1f ms without (first frame %.1f ms)\n", p.c_str(),
              r.frame_skip_ms, r.frame_noskip_ms, first_ms);
  std::printf(
      "%s: samples per frame %llu with skipping (mean %.1f, max %u per pixel), %llu "
      "without (mean %.1f, max %u)\n",
      p.c_str(), (unsigned long long)st_skip.samples_total, st_skip.samples_mean,
      st_skip.samples_max, (unsigned long long)st_noskip.samples_total, st_noskip.samples_mean,
      st_noskip.samples_max);
  b.report.figure(p + "_frame_ms", r.frame_skip_ms);
  b.report.baseline(p + "_frame_noskip_ms", r.frame_noskip_ms);
  b.report.figure(p + "_first_frame_ms", first_ms);
  b.report.figure(p + "_samples", double(r.samples_skip));
  b.report.baseline(p + "_samples_noskip", double(r.samples_noskip));
  b.report.figure(p + "_skip_speedup", r.frame_noskip_ms / r.frame_skip_ms);
  b.report.figure(p + "_skip_sample_ratio", double(r.samples_noskip) / double(r.samples_skip));
  return r;
}

// The scale used while the camera moves: config/render.toml's motion.moving_scale.
float configuredMovingScale() {
  float moving_scale = RenderConfig{}.moving_scale;
  try {
    if (std::filesystem::exists(configFile("render.toml")))
      moving_scale = loadRenderConfig(configFile("render.toml")).moving_scale;
  } catch (const std::exception& e) {
    std::printf("  (render.toml: %s; using the built-in moving scale)\n", e.what());
  }
  return moving_scale;
}

// Orbit: a moving camera renders at reduced resolution (RenderOptions::scale). The fps at the
// configured moving scale (into *moving_scale).
double benchOrbit(RenderBench& b, const Volume& cumulus, float* moving_scale_out) {
  b.renderer.sync(cumulus, b.light);
  std::printf("\norbit (cumulus, camera moving 3° a frame):\n");
  const float moving_scale = *moving_scale_out = configuredMovingScale();
  double orbit_fps_default = 0;
  std::vector<float> scales{1.0f, 0.5f, 0.35f, 0.25f};
  if (std::find(scales.begin(), scales.end(), moving_scale) == scales.end())
    scales.push_back(moving_scale);
  for (float scale : scales) {
    RenderOptions opt;
    opt.scale = scale;
    opt.finish = true;
    const int orbit_frames = std::max(b.frames * 2, 8);
    b.renderer.render(b.camera, b.width, b.height, b.target.fbo(), opt);  // warm-up (low-res)
    double c0 = processCpuMs();
    double ms = timeMs([&] {
      for (int i = 0; i < orbit_frames; ++i)
        b.renderer.render(b.camera.orbited(3.0f * float(i + 1)), b.width, b.height, b.target.fbo(),
                          opt);
    });
    double cpu_per_frame = (processCpuMs() - c0) / orbit_frames;
    double fps = 1000.0 * orbit_frames / ms;
    std::printf("  scale %.2f (%dx%d ray cast): %.1f fps (process CPU %.1f ms a frame)\n", scale,
                b.renderer.lastStats().width, b.renderer.lastStats().height, fps, cpu_per_frame);
    char key[64];
    std::snprintf(key, sizeof key, "orbit_fps_scale_%03d", int(std::lround(scale * 100)));
    b.report.figure(key, fps);
    if (scale == moving_scale) orbit_fps_default = fps;
  }
  return orbit_fps_default;
}

struct LightResult {
  double sweep_ms = 0, ref_ms = 0, mae = 0;
};

// Light volume: full recompute by the sweep vs the reference march of Alg. 5.
LightResult benchLight(RenderBench& b, const Volume& cumulus) {
  const Light& light = b.light;
  std::printf("\nlight volume %d³ (cumulus, default light):\n", b.n);
  std::vector<double> sweep_times, sweep_cpu;
  LightVolume lv;
  sweepLightVolume(lv, cumulus, light, cumulus.bounds());
  Light moved = light;
  for (int i = 0; i < 3; ++i) {
    // A light change: full recompute.
    moved.direction = glm::normalize(light.direction + glm::vec3(0.003f * float(i + 1), 0, 0));
    double c0 = processCpuMs();
    sweep_times.push_back(timeMs([&] { sweepLightVolume(lv, cumulus, moved, {}); }));
    sweep_cpu.push_back(processCpuMs() - c0);
  }
  // The same on one thread: the work itself, without the threads' pipeline waits.
  std::vector<double> single_times;
  setWorkerThreads(1);
  for (int i = 0; i < 3; ++i) {
    moved.direction = glm::normalize(light.direction - glm::vec3(0.003f * float(i + 1), 0, 0));
    single_times.push_back(timeMs([&] { sweepLightVolume(lv, cumulus, moved, {}); }));
  }
  setWorkerThreads(0);
  sweepLightVolume(lv, cumulus, light, {});
  LightResult r;
  r.sweep_ms = median(sweep_times);
  std::printf(
      "  sweep (light change, full recompute): %.1f ms wall, %.1f ms process CPU (%d threads); "
      "%.1f ms wall on 1 thread\n",
      r.sweep_ms, median(sweep_cpu), workerThreads(), median(single_times));
  b.report.figure("light_sweep_cpu_ms", median(sweep_cpu));
  b.report.figure("light_sweep_1thread_ms", median(single_times));
  const int z_step = b.n >= 128 ? 32 : 1;
  std::vector<float> ref;
  double ref_sampled_ms = timeMs([&] { ref = marchLightReference(cumulus, light, z_step); });
  r.ref_ms = ref_sampled_ms * z_step;
  // Compared where the light volume is defined: the light bricks the renderer reads (past a
  // column's lowest one the shadow falls on nothing and is not stored; light_accuracy.h).
  const LightAccuracy accuracy = compareWithReference(lv, cumulus, ref);
  r.mae = accuracy.mae;
  std::printf(
      "  sweep %.1f ms; reference march %.0f ms (%s); MAE %.4f over the %zu voxels of the "
      "light bricks (%.4f over the %zu not fully lit; %zu voxels outside them not compared)\n",
      r.sweep_ms, r.ref_ms, z_step > 1 ? "timed on every 32nd z slice, x32" : "all voxels", r.mae,
      accuracy.voxels, accuracy.shadowed_mae, accuracy.shadowed_voxels, accuracy.unread_voxels);
  b.report.figure("light_sweep_ms", r.sweep_ms);
  b.report.baseline("light_reference_march_ms", r.ref_ms);
  b.report.figure("light_speedup", r.ref_ms / r.sweep_ms);
  b.report.figure("light_mae_vs_reference", r.mae);
  b.report.figure("light_mae_shadowed_voxels", accuracy.shadowed_mae);
  return r;
}

// Incremental update: a 24³ block changes in the middle of the cloud (its shadow falls into
// cloud that is already dark) and on the cloud's lit upper side (its shadow crosses the cloud).
// Pen-up → volume and light ready is occupancy + light + pack + upload.
void benchEdits(RenderBench& b, const Volume& cumulus) {
  const int n = b.n;
  const struct {
    const char* name;
    glm::ivec3 centre;
  } edits[] = {{"edit24", glm::ivec3(n / 2)},
               {"edit24_lit_side", glm::ivec3(n / 2, 3 * n / 4, n / 2)}};
  for (const auto& edit : edits) {
    Volume edited = cumulus;
    VoxelBox block{edit.centre - 12, edit.centre + 12};
    auto fill = [&](float value) {
      for (int z = block.lo.z; z < block.hi.z; ++z)
        for (int y = block.lo.y; y < block.hi.y; ++y)
          for (int x = block.lo.x; x < block.hi.x; ++x) edited.voxelForWrite(x, y, z) = value;
      edited.markDirty(block);
    };
    fill(0.0f);
    b.renderer.sync(edited, b.light);
    fill(1.0f);
    const double c0 = processCpuMs();
    const auto t0 = Clock::now();
    SyncStats inc = b.renderer.sync(edited, b.light);
    const double total_ms = msSince(t0), total_cpu = processCpuMs() - c0;
    std::printf(
        "  %s at (%d,%d,%d): occupancy %.2f ms, light %.2f ms (%lld voxels), pack %.2f ms, "
        "upload %.2f ms; sync %.1f ms wall, %.1f ms process CPU\n",
        edit.name, edit.centre.x, edit.centre.y, edit.centre.z, inc.occupancy_ms, inc.light_ms,
        inc.light_box.voxelCount(), inc.pack_ms, inc.upload_ms, total_ms, total_cpu);
    const std::string p = edit.name;
    b.report.figure(p + "_occupancy_ms", inc.occupancy_ms);
    b.report.figure(p + "_light_ms", inc.light_ms);
    b.report.figure(p + "_light_voxels", double(inc.light_box.voxelCount()));
    b.report.figure(p + "_pack_ms", inc.pack_ms);
    b.report.figure(p + "_upload_ms", inc.upload_ms);
    b.report.figure(p + "_sync_ms", total_ms);
    b.report.figure(p + "_sync_cpu_ms", total_cpu);
  }
}

// vdb_render's ray-tracing time of one scene (same camera: -translate/-lookat, horizontal -fov,
// -step 1), or a negative value when the conversion failed.
double vdbRenderMs(const RenderBench& b, const std::string& converter, const Volume& v,
                   const char* name) {
  const float aspect = float(b.width) / float(b.height);
  const float hfov = 2.0f * std::atan(std::tan(glm::radians(b.camera.fov_y_deg) / 2) * aspect);
  const std::string dir = std::filesystem::temp_directory_path().string();
  const std::string base = dir + "/cb_bench_" + std::to_string(getpid()) + "_" + name;
  const std::string vol = base + ".cbvol", vdbf = base + ".vdb", img = base + "_vdb.png";
  saveVolume(v, vol);
  std::string out;
  if (runCommand("'" + converter + "' '" + vol + "' '" + vdbf + "'", &out) != 0) {
    std::printf("  converter failed: %s\n", out.c_str());
    return -1;
  }
  const Camera& camera = b.camera;
  char cmd[1024];
  std::snprintf(cmd, sizeof cmd,
                "vdb_render '%s' '%s' -translate %g,%g,%g -lookat %g,%g,%g -up 0,1,0 "
                "-fov %g -res %dx%d -step 1 -v",
                vdbf.c_str(), img.c_str(), camera.eye.x, camera.eye.y, camera.eye.z,
                camera.target.x, camera.target.y, camera.target.z, glm::degrees(hfov), b.width,
                b.height);
  double wall = timeMs([&] { runCommand(cmd, &out); });
  // vdb_render -v prints "ray-tracing density...\n...completed in X sec".
  double trace_s = -1;
  auto pos = out.find("ray-tracing");
  if (pos != std::string::npos) {
    auto c = out.find("completed in", pos);
    if (c != std::string::npos) trace_s = std::atof(out.c_str() + c + 12);
  }
  const double ms = trace_s > 0 ? trace_s * 1000.0 : wall;
  std::printf("  %s: ray tracing %.0f ms (process wall time %.0f ms)\n", name, ms, wall);
  std::filesystem::remove(vol);
  std::filesystem::remove(vdbf);
  std::filesystem::remove(img);
  return ms;
}

// vdb_render on the same volumes, view and size; false when it did not run.
bool benchVdb(RenderBench& b, bool wanted, const Volume* scenes[2], const SceneResult results[2],
              double vdb_ms[2]) {
  const std::string converter = executableDir() + "/cloudbrush-volume-to-vdb";
  const bool vdb = wanted && access(converter.c_str(), X_OK) == 0 &&
                   std::system("command -v vdb_render >/dev/null 2>&1") == 0;
  if (!vdb) {
    std::printf("\nvdb_render comparison skipped (%s)\n",
                !wanted ? "--no-vdb" : "vdb_render or the converter missing");
    b.report.note("vdb_render", "skipped");
    return false;
  }
  std::printf("\nvdb_render (same camera: -translate/-lookat, horizontal -fov, -step 1):\n");
  for (int s = 0; s < 2; ++s) {
    const double ms = vdbRenderMs(b, converter, *scenes[s], kSceneNames[s]);
    if (ms < 0) continue;
    vdb_ms[s] = ms;
    b.report.baseline(std::string("vdb_render_") + kSceneNames[s] + "_ms", vdb_ms[s]);
    b.report.figure(std::string("vs_vdb_render_speedup_") + kSceneNames[s],
                    vdb_ms[s] / results[s].frame_skip_ms);
  }
  return true;
}

}  // namespace

int benchRender(int argc, char** argv) {
  Args args(argc, argv, {"help", "no-vdb"});
  if (args.has("help")) {
    std::printf("%s", kHelp);
    return 0;
  }
  int width = 1280, height = 720;
  if (auto s = args.get("size"); s && std::sscanf(s->c_str(), "%dx%d", &width, &height) != 2) {
    std::fprintf(stderr, "cloudbrush bench render: --size '%s': expected WxH\n", s->c_str());
    return 2;
  }
  const int frames = int(std::max(1L, args.getInt("frames", 5)));
  const int n = int(args.getInt("dims", 256));
  if (!args.error().empty() || n < 8 || n > 1024 || width < 1 || height < 1) {
    std::fprintf(stderr, "cloudbrush bench render: bad arguments %s\n", args.error().c_str());
    return 2;
  }
  BenchReport report("render");
  const double load_at_start = loadAverage();
  report.figure("load_average_1min_at_start", load_at_start);
  std::printf("bench render: %dx%d, %d³ volumes, reference camera, %d frames per figure\n", width,
              height, n, frames);

  Volume cumulus(glm::ivec3(1)), sparse(glm::ivec3(1));
  double gen_cumulus = timeMs([&] { cumulus = makeBundledCumulus(glm::ivec3(n), 1); });
  double gen_sparse = timeMs([&] { sparse = makeSparsePuffs(glm::ivec3(n), 2); });
  std::printf("scenes: cumulus %.1f%% filled (generated in %.0f ms), sparse %.2f%% (%.0f ms)\n",
              100 * filledFraction(cumulus), gen_cumulus, 100 * filledFraction(sparse), gen_sparse);
  report.figure("generate_cumulus_ms", gen_cumulus);
  report.figure("cumulus_filled_fraction", filledFraction(cumulus));
  report.figure("sparse_filled_fraction", filledFraction(sparse));

  EglContext ctx;
  std::string error;
  if (!createSurfacelessContext(&ctx, &error)) {
    std::fprintf(stderr, "cloudbrush bench render: %s\n", error.c_str());
    return 1;
  }
  std::printf("GL: %s | %s\n", ctx.renderer.c_str(), ctx.version.c_str());
  report.note("gl_renderer", ctx.renderer);
  {
    VolumeRenderer renderer;
    RenderTarget target;
    if (!renderer.init(&error) ||
        !target.create(width, height, RenderTarget::Format::kRgba8, &error)) {
      std::fprintf(stderr, "cloudbrush bench render: %s\n", error.c_str());
      destroyGlContext(&ctx);
      return 1;
    }
    RenderBench b(renderer, target, report, width, height, frames, n);
    const Volume* scenes[2] = {&cumulus, &sparse};
    SceneResult results[2];
    for (int s = 0; s < 2; ++s) results[s] = benchScene(b, *scenes[s], kSceneNames[s]);
    float moving_scale = 0.0f;
    const double orbit_fps_default = benchOrbit(b, cumulus, &moving_scale);
    const LightResult light = benchLight(b, cumulus);
    benchEdits(b, cumulus);
    double vdb_ms[2] = {0, 0};
    const bool vdb = benchVdb(b, !args.has("no-vdb"), scenes, results, vdb_ms);

    std::printf("\ntargets (this machine, llvmpipe):\n");
    printTarget("fresh full-res lit frame, cumulus", results[0].frame_skip_ms, "ms", 100, true);
    char orbit_label[64];
    std::snprintf(orbit_label, sizeof orbit_label, "orbit fps at moving_scale %.2f", moving_scale);
    printTarget(orbit_label, orbit_fps_default, "fps", 20, false);
    printTarget("skipping: fewer samples on sparse (ratio)",
                double(results[1].samples_noskip) / double(results[1].samples_skip), "x", 3, false);
    printTarget("skipping: faster on sparse (ratio)",
                results[1].frame_noskip_ms / results[1].frame_skip_ms, "x", 2, false);
    printTarget("light volume full recompute", light.sweep_ms, "ms", 50, true);
    printTarget("light sweep vs reference march (ratio)", light.ref_ms / light.sweep_ms, "x", 20,
                false);
    printTarget("light MAE vs reference march", light.mae, "", 0.01, true);
    if (vdb) {
      printTarget("vs vdb_render, cumulus (ratio)", vdb_ms[0] / results[0].frame_skip_ms, "x", 5,
                  false);
      printTarget("vs vdb_render, sparse (ratio)", vdb_ms[1] / results[1].frame_skip_ms, "x", 5,
                  false);
    }
  }
  destroyGlContext(&ctx);
  std::printf(
      "load average (1 min) at start %.2f, at end %.2f on %ld cores: other processes share "
      "this machine, so wall times above include their load\n",
      load_at_start, loadAverage(), sysconf(_SC_NPROCESSORS_ONLN));
  report.figure("load_average_1min_at_end", loadAverage());
  report.print();
  return 0;
}

}  // namespace cb
