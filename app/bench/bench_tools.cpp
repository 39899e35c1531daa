// `cloudbrush bench tools`: picture → cloud (512×512 silhouette into 256³), model → cloud (the
// generated 70,656-triangle torus), morph in-between generation at 256³ and one wind step (64³
// velocity driving the 256³ density), each against a straightforward baseline in the same run.
// Times are to the volume ready (dirty box marked); the lit frame after it is the painter's sync,
// timed by `bench mapping`.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <vector>

#include "app/bench/bench_report.h"
#include "app/bench/benches.h"
#include "app/core/parallel_for.h"
#include "app/render/image_io.h"
#include "app/tools/cloud_morph.h"
#include "app/tools/model_cloud.h"
#include "app/tools/picture_cloud.h"
#include "app/tools/procedural_mesh.h"
#include "app/tools/wind.h"

namespace cb {
namespace {

double timeMs(const std::function<void()>& fn) {
  const auto t0 = std::chrono::steady_clock::now();
  fn();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

std::vector<uint8_t> silhouette(int w, int h) {
  struct Disc {
    float x, y, r;
  };
  const Disc discs[] = {{0.30f, 0.62f, 0.20f}, {0.50f, 0.45f, 0.28f}, {0.70f, 0.60f, 0.20f},
                        {0.40f, 0.70f, 0.16f}, {0.62f, 0.72f, 0.15f}, {0.82f, 0.70f, 0.10f}};
  std::vector<uint8_t> rgba(size_t(w) * h * 4, 255);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (const Disc& d : discs) {
        const float dx = x + 0.5f - d.x * w, dy = y + 0.5f - d.y * h,
                    r = d.r * float(std::min(w, h));
        if (dx * dx + dy * dy <= r * r) {
          uint8_t* p = &rgba[(size_t(y) * w + x) * 4];
          p[0] = p[1] = p[2] = 20;
        }
      }
  return rgba;
}

}  // namespace

int benchTools(int argc, char** argv) {
  const int runs = argc > 1 && std::string(argv[1]) == "--quick" ? 1 : 3;
  BenchReport report("tools");
  const auto dir = std::filesystem::temp_directory_path();
  ToolView view;
  view.camera = Camera::reference();

  // Picture → cloud.
  ImageRgba8 image;
  image.width = image.height = 512;
  image.pixels = silhouette(512, 512);
  const std::string png = (dir / "cloudbrush-bench-silhouette.png").string();
  writePng(png, image);
  std::vector<double> picture, picture_base;
  for (int r = 0; r < runs; ++r) {
    Volume volume;
    picture.push_back(timeMs([&] { pictureToCloud(png, view, PictureCloudParams{}, &volume); }));
    Volume base;
    PictureCloudParams naive;
    naive.naive_uniform_depth = true;
    setWorkerThreads(1);
    picture_base.push_back(timeMs([&] { pictureToCloud(png, view, naive, &base); }));
    setWorkerThreads(0);
  }
  std::printf(
      "picture -> cloud 512x512 into 256^3: %.1f ms (baseline, naive uniform depth, one "
      "thread: %.1f ms; target <= 300)\n",
      median(picture), median(picture_base));
  report.figure("picture_to_volume_ms", median(picture));
  report.baseline("picture_naive_one_thread_ms", median(picture_base));

  // Model → cloud.
  const TriangleMesh torus = makeDisplacedTorus(0.6f, 0.25f, 0.2f, 192, 184);
  const std::string obj = (dir / "cloudbrush-bench-torus.obj").string();
  writeObj(obj, torus);
  std::vector<double> model, model_base;
  for (int r = 0; r < runs; ++r) {
    Volume volume;
    model.push_back(timeMs([&] { modelToCloud(obj, view, ModelCloudParams{}, &volume); }));
    Volume base;
    setWorkerThreads(1);
    model_base.push_back(timeMs([&] { modelToCloud(obj, view, ModelCloudParams{}, &base); }));
    setWorkerThreads(0);
  }
  std::printf(
      "model -> cloud %zu triangles into 256^3 (load + check + voxelise): %.1f ms "
      "(baseline, one thread: %.1f ms; target <= 500)\n",
      torus.triangles.size(), median(model), median(model_base));
  report.figure("model_to_volume_ms", median(model));
  report.figure("model_triangles", double(torus.triangles.size()));
  report.baseline("model_one_thread_ms", median(model_base));

  // Morph between the picture's cloud and the model's cloud.
  Volume a, b;
  pictureToCloud(png, view, PictureCloudParams{}, &a);
  modelToCloud(obj, view, ModelCloudParams{}, &b);
  CloudMorph* plan = nullptr;
  const double plan_ms = timeMs([&] { plan = new CloudMorph(a, b); });
  std::vector<double> frame, fade;
  for (int r = 0; r < runs; ++r) {
    frame.push_back(timeMs([&] { plan->frame(0.37f + 0.1f * r); }));
    fade.push_back(timeMs([&] {
      Volume out(a.dims());
      const float t = 0.37f + 0.1f * r;
      for (size_t i = 0; i < out.voxelCount(); ++i)
        out.data()[i] = (1 - t) * a.data()[i] + t * b.data()[i];
      out.markDirty(out.bounds());
    }));
  }
  std::printf(
      "morph 256^3: plan %.1f ms (%zu particle pairs), in-between %.1f ms (baseline, "
      "per-voxel cross-fade: %.1f ms)\n",
      plan_ms, plan->pairCount(), median(frame), median(fade));
  report.figure("morph_plan_ms", plan_ms);
  report.figure("morph_inbetween_ms", median(frame));
  report.figure("morph_pairs", double(plan->pairCount()));
  report.baseline("crossfade_inbetween_ms", median(fade));
  delete plan;

  // Wind: one step of the 64³ velocity grid (self-advection + 20 Jacobi sweeps) driving the
  // picture's 256³ cloud, a breeze plus a gust; baseline the same step on one thread.
  auto windSteps = [&](std::vector<double>* velocity_ms, std::vector<double>* density_ms) {
    Volume cloud = a;
    WindSolver wind(cloud.worldMin(), cloud.worldMax());
    wind.setUniformWind({0.15f, 0.0f, 0.05f});
    wind.addForce({0.0f, 1.5f, 0.0f}, glm::vec3(0.0f), 0.5f, 0.1f);
    for (int r = 0; r < runs + 1; ++r) {  // the first step faults the scratch grid in
      const double v = timeMs([&] { wind.stepVelocity(1.0f / 15); });
      const double d = timeMs([&] { wind.advectDensity(1.0f / 15, &cloud); });
      if (r == 0) continue;
      velocity_ms->push_back(v);
      density_ms->push_back(d);
    }
  };
  std::vector<double> wind_velocity, wind_density, wind_velocity_base, wind_density_base;
  windSteps(&wind_velocity, &wind_density);
  setWorkerThreads(1);
  windSteps(&wind_velocity_base, &wind_density_base);
  setWorkerThreads(0);
  const double wind_step = median(wind_velocity) + median(wind_density);
  const double wind_step_base = median(wind_velocity_base) + median(wind_density_base);
  std::printf(
      "wind step 64^3 velocity driving 256^3 density: %.1f ms (velocity %.1f, density %.1f; "
      "baseline, one thread: %.1f ms; target: step + lit frame at scale 0.5 <= 66.7 ms)\n",
      wind_step, median(wind_velocity), median(wind_density), wind_step_base);
  report.figure("wind_step_ms", wind_step);
  report.figure("wind_velocity_ms", median(wind_velocity));
  report.figure("wind_density_ms", median(wind_density));
  report.baseline("wind_step_one_thread_ms", wind_step_base);
  report.print();
  return 0;
}

}  // namespace cb
