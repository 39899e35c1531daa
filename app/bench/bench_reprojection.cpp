#include "app/bench/bench_reprojection.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "app/bench/bench_report.h"
#include "app/render/render_target.h"
#include "app/render/temporal_reprojection.h"

namespace cb {
namespace {

constexpr int kBlockFrames = 8;
constexpr float kDegreesPerFrame = 3.0f;

// The largest channel difference of each pixel.
std::vector<double> pixelDifferences(const ImageRgba8& a, const ImageRgba8& b) {
  std::vector<double> d(a.pixels.size() / 4);
  for (size_t i = 0; i < d.size(); ++i) {
    int m = 0;
    for (size_t c = 0; c < 4; ++c)
      m = std::max(m, std::abs(int(a.pixels[i * 4 + c]) - int(b.pixels[i * 4 + c])));
    d[i] = m;
  }
  return d;
}

void addError(const std::vector<double>& d, double* mean, double* p99) {
  double sum = 0;
  for (double v : d) sum += v;
  std::vector<double> s = d;
  const size_t k = size_t(0.99 * double(s.size() - 1));
  std::nth_element(s.begin(), s.begin() + long(k), s.end());
  *mean += sum / double(d.size());
  *p99 = std::max(*p99, s[k]);
}

}  // namespace

ReprojectedOrbitFigures measureReprojectedOrbit(VolumeRenderer& renderer, const Camera& view,
                                                int width, int height, int factor, int blocks,
                                                const std::string& shots_dir) {
  ReprojectedOrbitFigures fig;
  fig.factor = factor;
  TemporalReprojection reprojection;
  RenderTarget target;
  std::string error;
  if (!reprojection.init(&error) ||
      !target.create(width, height, RenderTarget::Format::kRgba8, &error)) {
    std::printf("  reprojected orbit: %s\n", error.c_str());
    return fig;
  }
  RenderOptions half;
  half.scale = 0.5f;
  half.moving = true;
  half.finish = true;
  RenderOptions detail = half;
  detail.cast_at_volume_detail = true;
  RenderOptions cast;
  cast.finish = true;
  std::vector<double> ms, cpu, base_ms, base_cpu, detail_ms, detail_cpu, cast_ms, pass_ms, copy_ms;
  int frame = 0;
  // Alternating blocks: the baseline's frames, the detail's, then as many reprojected ones (a
  // frame costs the same with or without history: every pixel runs the whole reprojection pass).
  for (int b = 0; b < blocks; ++b) {
    for (const RenderOptions* options : {&half, &detail})
      for (int i = 0; i < kBlockFrames; ++i, ++frame) {
        const double c0 = processCpuMs();
        renderer.render(view.orbited(kDegreesPerFrame * float(frame)), width, height, target.fbo(),
                        *options);
        if (b == 0 && i == 0) continue;  // the first frame compiles the programs
        (options == &half ? base_cpu : detail_cpu).push_back(processCpuMs() - c0);
        (options == &half ? base_ms : detail_ms).push_back(renderer.lastStats().frame_ms);
      }
    reprojection.invalidate();  // the view jumped over the baseline's block
    for (int i = 0; i < kBlockFrames; ++i, ++frame) {
      const double c0 = processCpuMs();
      reprojection.render(renderer, view.orbited(kDegreesPerFrame * float(frame)), width, height,
                          target.fbo(), cast, factor);
      if (b == 0 && i == 0) continue;  // the first frame compiles the programs
      cpu.push_back(processCpuMs() - c0);
      const ReprojectionStats stats = reprojection.lastStats();
      ms.push_back(stats.frame_ms);
      cast_ms.push_back(stats.cast_ms);
      pass_ms.push_back(stats.reproject_ms);
      copy_ms.push_back(stats.copy_ms);
    }
  }
  fig.ms = median(ms);
  fig.cpu_ms = median(cpu);
  fig.base_ms = median(base_ms);
  fig.base_cpu_ms = median(base_cpu);
  fig.detail_ms = median(detail_ms);
  fig.detail_cpu_ms = median(detail_cpu);
  fig.detail_scale = renderer.castScale(view, height, detail);
  fig.cast_ms = median(cast_ms);
  fig.reproject_ms = median(pass_ms);
  fig.copy_ms = median(copy_ms);

  // Error: reprojected frames of a continued orbit against full casts of their cameras.
  reprojection.invalidate();
  RenderTarget full;
  full.create(width, height, RenderTarget::Format::kRgba8, &error);
  fig.error_mean = fig.error_p99 = fig.base_error_mean = fig.base_error_p99 = 0;
  fig.detail_error_mean = fig.detail_error_p99 = 0;
  const int measured = 4;
  for (int i = 0; i < factor * factor + 2 * measured; ++i) {
    const Camera cam = view.orbited(kDegreesPerFrame * float(i));
    reprojection.render(renderer, cam, width, height, target.fbo(), RenderOptions{}, factor);
    if (i < factor * factor || (i - factor * factor) % 2) continue;
    const ImageRgba8 image = target.readRgba8();
    renderer.render(cam, width, height, full.fbo(), RenderOptions{});
    const ImageRgba8 reference = full.readRgba8();
    RenderTarget low;
    low.create(width, height, RenderTarget::Format::kRgba8, &error);
    renderer.render(cam, width, height, low.fbo(), half);
    const ImageRgba8 reduced = low.readRgba8();
    renderer.render(cam, width, height, low.fbo(), detail);
    const ImageRgba8 at_detail = low.readRgba8();
    addError(pixelDifferences(image, reference), &fig.error_mean, &fig.error_p99);
    addError(pixelDifferences(reduced, reference), &fig.base_error_mean, &fig.base_error_p99);
    addError(pixelDifferences(at_detail, reference), &fig.detail_error_mean, &fig.detail_error_p99);
    if (!shots_dir.empty()) {
      char name[256];
      std::snprintf(name, sizeof name, "%s/%dx%d_f%d_frame%02d_", shots_dir.c_str(), width, height,
                    factor, i);
      writePng(std::string(name) + "reprojected.png", image);
      writePng(std::string(name) + "full_cast.png", reference);
      writePng(std::string(name) + "half_resolution.png", reduced);
      writePng(std::string(name) + "at_detail.png", at_detail);
    }
  }
  fig.error_mean /= measured;
  fig.base_error_mean /= measured;
  fig.detail_error_mean /= measured;
  return fig;
}

}  // namespace cb
