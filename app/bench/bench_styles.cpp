// cloudbrush bench styles: every render style (app/render/render_style.h) on the bundled cumulus
// at 256³, 1280×720, the reference camera and the default sun. Each style's fresh full frame
// (wall time with glFinish, and process CPU time: llvmpipe's threads included) against the
// thesis style measured in the same run, frames interleaved style by style so a busy machine
// slows every style alike. Also the moving frame (reduced scale, `moving` set) and the painting
// frame: the painter's cached still scene of that style with the live brush footprint and cursor
// composited over it (FootprintOverlay, as app/shell/painter/paint_screen.cpp draws while the pen
// is down), a disc footprint moving 6 px per frame. Targets: a full frame costs at most 1.5× the
// thesis style's; the painting frame stays ≥ 60 fps. --sky KIND puts that sky behind every style.
// Never fails on a target.
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "app/bench/bench_report.h"
#include "app/bench/benches.h"
#include "app/cli/args.h"
#include "app/render/footprint_overlay.h"
#include "app/render/gl/egl_context.h"
#include "app/render/image_io.h"
#include "app/render/render_config.h"
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
    "  --paint-frames N   timed painting frames per style (default 60)\n"
    "  --sky KIND         none|colour|lic: the sky behind every style (default none)\n"
    "  --config FILE      a render.toml whose [sky], [style.NAME] and [light] apply (over --sky)\n"
    "  --camera EX,EY,EZ,TX,TY,TZ,FOV  instead of the reference camera\n"
    "  --out-dir DIR      also write each style's frame as DIR/style-NAME.png\n";

constexpr double kTargetRatio = 1.5;

struct StyleTimes {
  std::vector<double> frame_ms, cpu_ms, moving_ms, painting_ms;
  double first_ms = 0;  // the first frame: llvmpipe compiles the style's programs
};

// The bench's settings, from the command line.
struct StylesBench {
  int width = 1280, height = 720, frames = 7, n = 256, paint_frames = 60;
  float moving_scale = 0.25f;
  std::string out_dir;
  SkySettings sky;
  StyleParams style_params;
  Light light;
  Camera camera = Camera::reference();
};

// Reads the options into *b: -1 when they hold, else the exit status (said on stderr).
int parseStylesBench(Args& args, StylesBench* b) {
  if (auto s = args.get("size");
      s && std::sscanf(s->c_str(), "%dx%d", &b->width, &b->height) != 2) {
    std::fprintf(stderr, "cloudbrush bench styles: --size '%s': expected WxH\n", s->c_str());
    return 2;
  }
  b->frames = int(std::max(1L, args.getInt("frames", 7)));
  b->n = int(args.getInt("dims", 256));
  b->moving_scale = float(args.getDouble("moving-scale", 0.25));
  b->out_dir = args.get("out-dir", "");
  b->paint_frames = int(std::max(1L, args.getInt("paint-frames", 60)));
  if (!parseSkyKind(args.get("sky", "none"), &b->sky.kind) || b->sky.kind == SkyKind::kImage) {
    std::fprintf(stderr, "cloudbrush bench styles: --sky: expected none, colour or lic\n");
    return 2;
  }
  if (auto config = args.get("config")) {
    try {
      const RenderConfig c = loadRenderConfig(*config);
      b->sky = c.options.sky;
      b->style_params = c.options.style_params;
      b->light = c.light;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "cloudbrush bench styles: %s\n", e.what());
      return 2;
    }
  }
  if (auto text = args.get("camera")) {
    float v[7];
    if (std::sscanf(text->c_str(), "%f,%f,%f,%f,%f,%f,%f", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5],
                    &v[6]) != 7 ||
        !(v[6] > 0.0f && v[6] < 180.0f)) {
      std::fprintf(stderr,
                   "cloudbrush bench styles: --camera '%s': expected EX,EY,EZ,TX,TY,TZ,FOV\n",
                   text->c_str());
      return 2;
    }
    b->camera.eye = {v[0], v[1], v[2]};
    b->camera.target = {v[3], v[4], v[5]};
    b->camera.fov_y_deg = v[6];
  }
  if (!args.error().empty() || b->n < 8 || b->n > 1024 || b->width < 1 || b->height < 1 ||
      !(b->moving_scale >= 0.05f && b->moving_scale <= 1.0f)) {
    std::fprintf(stderr, "cloudbrush bench styles: bad arguments %s\n", args.error().c_str());
    return 2;
  }
  return -1;
}

// One style's frame options: full (scale 1) or moving (the reduced scale, `moving` set).
RenderOptions styleOptions(const StylesBench& b, RenderStyle style, bool moving) {
  RenderOptions o;
  o.style = style;
  o.finish = true;
  o.moving = moving;
  o.scale = moving ? b.moving_scale : 1.0f;
  o.sky = b.sky;
  o.style_params = b.style_params;
  return o;
}

// Each style's first frame (and --out-dir's PNG), then the timed full and moving frames,
// interleaved style by style.
void timeStyleFrames(const StylesBench& b, VolumeRenderer& renderer, RenderTarget& target,
                     std::vector<StyleTimes>* times) {
  const int width = b.width, height = b.height;
  for (size_t i = 0; i < kAllRenderStyles.size(); ++i) {
    renderer.render(b.camera, width, height, target.fbo(),
                    styleOptions(b, kAllRenderStyles[i], false));
    (*times)[i].first_ms = renderer.lastStats().frame_ms;
    renderer.render(b.camera, width, height, target.fbo(),
                    styleOptions(b, kAllRenderStyles[i], true));
    if (!b.out_dir.empty()) {
      renderer.render(b.camera, width, height, target.fbo(),
                      styleOptions(b, kAllRenderStyles[i], false));
      std::filesystem::create_directories(b.out_dir);
      const std::string path =
          b.out_dir + "/style-" + renderStyleName(kAllRenderStyles[i]) + ".png";
      writePng(path, target.readRgba8());
      std::printf("wrote %s\n", path.c_str());
    }
  }
  for (int f = 0; f < b.frames; ++f)
    for (size_t i = 0; i < kAllRenderStyles.size(); ++i) {
      const double c0 = processCpuMs();
      renderer.render(b.camera, width, height, target.fbo(),
                      styleOptions(b, kAllRenderStyles[i], false));
      (*times)[i].cpu_ms.push_back(processCpuMs() - c0);
      (*times)[i].frame_ms.push_back(renderer.lastStats().frame_ms);
      renderer.render(b.camera, width, height, target.fbo(),
                      styleOptions(b, kAllRenderStyles[i], true));
      (*times)[i].moving_ms.push_back(renderer.lastStats().frame_ms);
    }
}

// The painting frame: each style's still scene cached once (as the painter does), then
// footprint + cursor composited over it every frame; styles interleaved frame by frame,
// each with its own overlay (its own composite of its own scene).
void timePaintingFrames(const StylesBench& b, VolumeRenderer& renderer, BenchReport* report,
                        std::vector<StyleTimes>* times) {
  const int width = b.width, height = b.height;
  std::string error;
  const size_t count = kAllRenderStyles.size();
  std::vector<RenderTarget> scenes(count);
  std::vector<std::unique_ptr<FootprintOverlay>> overlays(count);
  RenderTarget frame;
  bool ready = frame.create(width, height, RenderTarget::Format::kRgba8, &error);
  for (size_t i = 0; ready && i < count; ++i) {
    overlays[i] = std::make_unique<FootprintOverlay>();
    ready = scenes[i].create(width, height, RenderTarget::Format::kRgba8, &error) &&
            overlays[i]->init(&error);
    if (!ready) break;
    renderer.render(b.camera, width, height, scenes[i].fbo(),
                    styleOptions(b, kAllRenderStyles[i], false));
    overlays[i]->beginFootprint(width, height);
  }
  if (!ready) {
    std::printf("painting frame: GL setup failed: %s\n", error.c_str());
    report->note("painting_frame", "GL setup failed: " + error);
  }
  Footprint footprint(width, height);
  const int radius = 18;
  for (int f = 0; ready && f < b.paint_frames; ++f) {
    // A stroke across the middle of the frame, 6 px per frame.
    const glm::ivec2 centre(width / 5 + (6 * f) % (3 * width / 5), height / 2);
    FootprintRect rect{centre.x - radius, centre.y - radius, centre.x + radius + 1,
                       centre.y + radius + 1};
    rect = rect.clipped(width, height);
    for (int y = rect.y0; y < rect.y1; ++y)
      for (int x = rect.x0; x < rect.x1; ++x) {
        const float d = glm::length(glm::vec2(x - centre.x, y - centre.y)) / float(radius);
        footprint.at(x, y) = std::max(footprint.at(x, y), std::clamp(1.0f - d, 0.0f, 1.0f));
      }
    OverlayCursor cursor;
    cursor.screen_px = glm::vec2(centre);
    for (size_t i = 0; i < count; ++i) {
      const auto t0 = std::chrono::steady_clock::now();
      overlays[i]->upload(footprint, rect);
      overlays[i]->draw(scenes[i].texture(), frame.fbo(), width, height, cursor);
      glFinish();
      (*times)[i].painting_ms.push_back(
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    }
  }
}

// The table, the figures against the thesis style, and the targets MET or MISSED.
void reportStyleTimes(const std::vector<StyleTimes>& times, BenchReport* report) {
  const double thesis_ms = median(times[0].frame_ms);
  const double thesis_cpu = median(times[0].cpu_ms);
  const double thesis_moving = median(times[0].moving_ms);
  report->baseline("thesis_frame_ms", thesis_ms);
  report->baseline("thesis_cpu_ms", thesis_cpu);
  report->baseline("thesis_moving_frame_ms", thesis_moving);
  const double thesis_painting = times[0].painting_ms.empty() ? 0.0 : median(times[0].painting_ms);
  report->baseline("thesis_painting_frame_ms", thesis_painting);
  std::printf("\n%-9s %10s %10s %9s %9s %12s %10s %12s %9s\n", "style", "frame ms", "CPU ms",
              "x thesis", "CPU x", "moving ms", "first ms", "painting ms", "x thesis");
  for (size_t i = 0; i < kAllRenderStyles.size(); ++i) {
    const std::string name = renderStyleName(kAllRenderStyles[i]);
    const double ms = median(times[i].frame_ms), cpu = median(times[i].cpu_ms);
    const double moving = median(times[i].moving_ms);
    const double painting = times[i].painting_ms.empty() ? 0.0 : median(times[i].painting_ms);
    std::printf("%-9s %10.1f %10.1f %9.2f %9.2f %12.1f %10.1f %12.2f %9.2f\n", name.c_str(), ms,
                cpu, ms / thesis_ms, cpu / thesis_cpu, moving, times[i].first_ms, painting,
                thesis_painting > 0.0 ? painting / thesis_painting : 0.0);
    if (i == 0) continue;
    report->figure(name + "_frame_ms", ms);
    report->figure(name + "_cpu_ms", cpu);
    report->figure(name + "_vs_thesis", ms / thesis_ms);
    report->figure(name + "_cpu_vs_thesis", cpu / thesis_cpu);
    report->figure(name + "_moving_frame_ms", moving);
    report->figure(name + "_first_frame_ms", times[i].first_ms);
    report->figure(name + "_painting_frame_ms", painting);
  }
  std::printf("\n");
  for (size_t i = 1; i < kAllRenderStyles.size(); ++i) {
    const double ratio = median(times[i].frame_ms) / thesis_ms;
    std::printf("  target %-9s full frame <= %.1fx thesis: %5.2fx %s\n",
                renderStyleName(kAllRenderStyles[i]), kTargetRatio, ratio,
                ratio <= kTargetRatio ? "MET" : "MISSED");
  }
  for (size_t i = 0; i < kAllRenderStyles.size(); ++i) {
    if (times[i].painting_ms.empty()) continue;
    const double fps = 1000.0 / median(times[i].painting_ms);
    std::printf("  target %-9s painting frame >= 60 fps: %6.0f fps %s\n",
                renderStyleName(kAllRenderStyles[i]), fps, fps >= 60.0 ? "MET" : "MISSED");
  }
}

}  // namespace

int benchStyles(int argc, char** argv) {
  Args args(argc, argv, {"help"});
  if (args.has("help")) {
    std::printf("%s", kHelp);
    return 0;
  }
  StylesBench b;
  if (const int status = parseStylesBench(args, &b); status >= 0) return status;
  std::printf("bench styles: %dx%d, cumulus %d³, %s camera, %d frames per style, sky %s\n", b.width,
              b.height, b.n, args.has("camera") ? "the given" : "reference", b.frames,
              skyKindName(b.sky.kind));
  BenchReport report("styles");
  const Volume cumulus = makeBundledCumulus(glm::ivec3(b.n), 1);

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
        !target.create(b.width, b.height, RenderTarget::Format::kRgba8, &error)) {
      std::fprintf(stderr, "cloudbrush bench styles: %s\n", error.c_str());
      status = 1;
    } else {
      renderer.sync(cumulus, b.light);
      std::vector<StyleTimes> times(kAllRenderStyles.size());
      timeStyleFrames(b, renderer, target, &times);
      timePaintingFrames(b, renderer, &report, &times);
      reportStyleTimes(times, &report);
    }
  }
  destroyGlContext(&ctx);
  if (status == 0) report.print();
  return status;
}

}  // namespace cb
