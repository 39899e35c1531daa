// cloudbrush bench styles: every render style (app/render/render_style.h) on the bundled cumulus
// at 256³, 1280×720, the reference camera and the default sun. Each style's fresh full frame
// (wall time with glFinish, and process CPU time: llvmpipe's threads included) against the
// thesis style measured in the same run, frames interleaved style by style so a busy machine
// slows every style alike. Also the moving frame (reduced scale, `moving` set). Target: a full
// frame costs at most 1.5× the thesis style's. Never fails on a target.
#include <time.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "app/bench/bench_report.h"
#include "app/bench/benches.h"
#include "app/cli/args.h"
#include "app/render/gl/egl_context.h"
#include "app/render/image_io.h"
#include "app/render/render_style.h"
#include "app/render/render_target.h"
#include "app/render/volume_renderer.h"
#include "app/volume/scene_generators.h"

namespace cb {
namespace {

const char kHelp[] =
    "usage: cloudbrush bench styles [--size WxH] [--frames N] [--dims N] [--moving-scale F]\n"
    "                               [--out-dir DIR]\n"
    "  --size WxH         image size (default 1280x720)\n"
    "  --frames N         timed frames per style, median reported (default 7)\n"
    "  --dims N           volume size N³ (default 256)\n"
    "  --moving-scale F   resolution scale of the moving frame (default 0.25, as render.toml)\n"
    "  --out-dir DIR      also write each style's frame as DIR/style-NAME.png\n";

constexpr double kTargetRatio = 1.5;

double processCpuMs() {
  timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) * 1e3 + double(t.tv_nsec) / 1e6;
}

struct StyleTimes {
  std::vector<double> frame_ms, cpu_ms, moving_ms;
  double first_ms = 0;  // the first frame: llvmpipe compiles the style's programs
};

}  // namespace

int benchStyles(int argc, char** argv) {
  Args args(argc, argv, {"help"});
  if (args.has("help")) {
    std::printf("%s", kHelp);
    return 0;
  }
  int width = 1280, height = 720;
  if (auto s = args.get("size"); s && std::sscanf(s->c_str(), "%dx%d", &width, &height) != 2) {
    std::fprintf(stderr, "cloudbrush bench styles: --size '%s': expected WxH\n", s->c_str());
    return 2;
  }
  const int frames = int(std::max(1L, args.getInt("frames", 7)));
  const int n = int(args.getInt("dims", 256));
  const float moving_scale = float(args.getDouble("moving-scale", 0.25));
  const std::string out_dir = args.get("out-dir", "");
  if (!args.error().empty() || n < 8 || n > 1024 || width < 1 || height < 1 ||
      !(moving_scale >= 0.05f && moving_scale <= 1.0f)) {
    std::fprintf(stderr, "cloudbrush bench styles: bad arguments %s\n", args.error().c_str());
    return 2;
  }
  std::printf("bench styles: %dx%d, cumulus %d³, reference camera, %d frames per style\n", width,
              height, n, frames);
  BenchReport report("styles");
  const Volume cumulus = makeBundledCumulus(glm::ivec3(n), 1);

  EglContext ctx;
  std::string error;
  if (!createSurfacelessContext(&ctx, &error)) {
    std::fprintf(stderr, "cloudbrush bench styles: %s\n", error.c_str());
    return 1;
  }
  std::printf("GL: %s | %s\n", ctx.renderer.c_str(), ctx.version.c_str());
  report.note("gl_renderer", ctx.renderer);
  int status = 0;
  {
    VolumeRenderer renderer;
    RenderTarget target;
    if (!renderer.init(&error) ||
        !target.create(width, height, RenderTarget::Format::kRgba8, &error)) {
      std::fprintf(stderr, "cloudbrush bench styles: %s\n", error.c_str());
      status = 1;
    } else {
      renderer.sync(cumulus, Light{});
      const Camera camera = Camera::reference();
      std::vector<StyleTimes> times(kAllRenderStyles.size());
      auto options = [&](RenderStyle style, bool moving) {
        RenderOptions o;
        o.style = style;
        o.finish = true;
        o.moving = moving;
        o.scale = moving ? moving_scale : 1.0f;
        return o;
      };
      for (size_t i = 0; i < kAllRenderStyles.size(); ++i) {
        renderer.render(camera, width, height, target.fbo(), options(kAllRenderStyles[i], false));
        times[i].first_ms = renderer.lastStats().frame_ms;
        renderer.render(camera, width, height, target.fbo(), options(kAllRenderStyles[i], true));
        if (!out_dir.empty()) {
          renderer.render(camera, width, height, target.fbo(), options(kAllRenderStyles[i], false));
          std::filesystem::create_directories(out_dir);
          const std::string path =
              out_dir + "/style-" + renderStyleName(kAllRenderStyles[i]) + ".png";
          writePng(path, target.readRgba8());
          std::printf("wrote %s\n", path.c_str());
        }
      }
      for (int f = 0; f < frames; ++f)
        for (size_t i = 0; i < kAllRenderStyles.size(); ++i) {
          const double c0 = processCpuMs();
          renderer.render(camera, width, height, target.fbo(), options(kAllRenderStyles[i], false));
          times[i].cpu_ms.push_back(processCpuMs() - c0);
          times[i].frame_ms.push_back(renderer.lastStats().frame_ms);
          renderer.render(camera, width, height, target.fbo(), options(kAllRenderStyles[i], true));
          times[i].moving_ms.push_back(renderer.lastStats().frame_ms);
        }
      const double thesis_ms = median(times[0].frame_ms);
      const double thesis_cpu = median(times[0].cpu_ms);
      const double thesis_moving = median(times[0].moving_ms);
      report.baseline("thesis_frame_ms", thesis_ms);
      report.baseline("thesis_cpu_ms", thesis_cpu);
      report.baseline("thesis_moving_frame_ms", thesis_moving);
      std::printf("\n%-9s %10s %10s %9s %9s %12s %10s\n", "style", "frame ms", "CPU ms", "x thesis",
                  "CPU x", "moving ms", "first ms");
      for (size_t i = 0; i < kAllRenderStyles.size(); ++i) {
        const std::string name = renderStyleName(kAllRenderStyles[i]);
        const double ms = median(times[i].frame_ms), cpu = median(times[i].cpu_ms);
        const double moving = median(times[i].moving_ms);
        std::printf("%-9s %10.1f %10.1f %9.2f %9.2f %12.1f %10.1f\n", name.c_str(), ms, cpu,
                    ms / thesis_ms, cpu / thesis_cpu, moving, times[i].first_ms);
        if (i == 0) continue;
        report.figure(name + "_frame_ms", ms);
        report.figure(name + "_cpu_ms", cpu);
        report.figure(name + "_vs_thesis", ms / thesis_ms);
        report.figure(name + "_cpu_vs_thesis", cpu / thesis_cpu);
        report.figure(name + "_moving_frame_ms", moving);
        report.figure(name + "_first_frame_ms", times[i].first_ms);
      }
      std::printf("\n");
      for (size_t i = 1; i < kAllRenderStyles.size(); ++i) {
        const double ratio = median(times[i].frame_ms) / thesis_ms;
        std::printf("  target %-9s full frame <= %.1fx thesis: %5.2fx %s\n",
                    renderStyleName(kAllRenderStyles[i]), kTargetRatio, ratio,
                    ratio <= kTargetRatio ? "MET" : "MISSED");
      }
    }
  }
  destroyGlContext(&ctx);
  if (status == 0) report.print();
  return status;
}

}  // namespace cb
