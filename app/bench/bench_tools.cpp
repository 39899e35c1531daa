// `cloudbrush bench tools`: picture → cloud (512×512 silhouette into 256³), model → cloud (the
// generated 70,656-triangle torus), morph in-between generation at 256³ and one wind step (64³
// velocity driving the 256³ density), each against a straightforward baseline in the same run;
// then the morph and the wind as the painter plays them (generate + renderer sync + ray cast at
// 1280×720, moving scale 0.5) against the first versions. Picture and model times are to the
// volume ready (dirty box marked); their lit frame is the painter's sync, timed by
// `bench mapping`.
#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <functional>
#include <memory>
#include <vector>

#include "app/bench/bench_report.h"
#include "app/bench/benches.h"
#include "app/core/parallel_for.h"
#include "app/render/gl/egl_context.h"
#include "app/render/image_io.h"
#include "app/render/render_target.h"
#include "app/render/volume_renderer.h"
#include "app/session/paint_session.h"
#include "app/shell/animation_preview.h"
#include "app/tools/cloud_animation.h"
#include "app/tools/cloud_morph.h"
#include "app/tools/model_cloud.h"
#include "app/tools/picture_cloud.h"
#include "app/tools/procedural_mesh.h"
#include "app/tools/wind.h"
#include "app/volume/volume_file.h"

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

  // Morph between the picture's cloud and the model's cloud, and wind on the picture's cloud:
  // the in-between / step alone, then as the painter plays them — generated, synced to the
  // renderer (upload, occupancy, light) and ray cast at 1280x720, moving scale 0.5.
  // Baselines in the same run: the first versions (the one-thread scatter into a fresh volume
  // per frame; the step sampling every voxel of the box).
  Volume a, b;
  pictureToCloud(png, view, PictureCloudParams{}, &a);
  modelToCloud(obj, view, ModelCloudParams{}, &b);
  std::unique_ptr<CloudMorph> plan;
  const double plan_ms = timeMs([&] { plan = std::make_unique<CloudMorph>(a, b); });
  const int frames = runs == 1 ? 3 : 6;
  std::vector<double> frame, frame_base, fade;
  const std::vector<float> dense_a = a.toDense(), dense_b = b.toDense();  // the cross-fade's grids
  Volume shown = a;
  VoxelBox written = shown.bounds();
  for (int r = 0; r < frames; ++r) {
    const float t = 0.2f + 0.1f * float(r);
    frame.push_back(timeMs([&] { written = plan->frameInto(t, &shown, written); }));
    frame_base.push_back(timeMs([&] { plan->frameOneThreadReference(t); }));
    fade.push_back(timeMs([&] {
      Volume out(a.dims());
      std::vector<float> mixed(dense_a.size());
      for (size_t i = 0; i < mixed.size(); ++i) mixed[i] = (1 - t) * dense_a[i] + t * dense_b[i];
      out.assignDense(mixed.data());
    }));
  }
  std::printf(
      "morph 256^3: plan %.1f ms (%zu particle pairs, %zu splats), in-between %.1f ms "
      "(baseline, first version: one thread, fresh volume: %.1f ms; per-voxel cross-fade: "
      "%.1f ms)\n",
      plan_ms, plan->pairCount(), plan->splatCount(), median(frame), median(frame_base),
      median(fade));
  report.figure("morph_plan_ms", plan_ms);
  report.figure("morph_inbetween_ms", median(frame));
  report.figure("morph_pairs", double(plan->pairCount()));
  report.figure("morph_splats", double(plan->splatCount()));
  report.baseline("morph_inbetween_first_version_ms", median(frame_base));
  report.baseline("crossfade_inbetween_ms", median(fade));

  // Wind: a breeze plus an updraft gust (the painter's WindAnimation) on the picture's cloud.
  auto windSteps = [&](bool every_voxel, std::vector<double>* velocity_ms,
                       std::vector<double>* density_ms, Volume* out) {
    Volume cloud = a;
    WindSolver wind(cloud.worldMin(), cloud.worldMax());
    wind.setUniformWind({0.25f, 0.0f, 0.0f});
    wind.addForce({0.0f, 1.5f, 0.0f}, glm::vec3(0.0f), 0.5f, 0.1f);
    for (int r = 0; r < frames + 1; ++r) {  // the first step faults the scratch grid in
      const double v = timeMs([&] { wind.stepVelocity(kWindStepSeconds); });
      const double d = timeMs([&] {
        if (every_voxel)
          wind.advectDensityEveryVoxel(kWindStepSeconds, &cloud);
        else
          wind.advectDensity(kWindStepSeconds, &cloud);
      });
      if (r == 0) continue;
      velocity_ms->push_back(v);
      density_ms->push_back(d);
    }
    *out = cloud;
  };
  std::vector<double> wind_velocity, wind_density, wind_velocity_base, wind_density_base;
  Volume blown, blown_base;
  windSteps(false, &wind_velocity, &wind_density, &blown);
  windSteps(true, &wind_velocity_base, &wind_density_base, &blown_base);
  const std::vector<float> blown_dense = blown.toDense(), blown_base_dense = blown_base.toDense();
  const bool same = std::memcmp(blown_dense.data(), blown_base_dense.data(),
                                blown_dense.size() * sizeof(float)) == 0;
  const double wind_step = median(wind_velocity) + median(wind_density);
  const double wind_step_base = median(wind_velocity_base) + median(wind_density_base);
  std::printf(
      "wind step 64^3 velocity driving 256^3 density: %.1f ms (velocity %.1f, density %.1f; "
      "baseline, first version sampling every voxel: %.1f ms, density %.1f; same bytes: %s)\n",
      wind_step, median(wind_velocity), median(wind_density), wind_step_base,
      median(wind_density_base), same ? "yes" : "NO");
  report.figure("wind_step_ms", wind_step);
  report.figure("wind_velocity_ms", median(wind_velocity));
  report.figure("wind_density_ms", median(wind_density));
  report.figure("wind_same_bytes_as_first_version", same ? 1.0 : 0.0);
  report.baseline("wind_step_first_version_ms", wind_step_base);
  report.baseline("wind_density_first_version_ms", median(wind_density_base));

  // As the painter plays them: generate + sync + render at 1280x720, scale 0.5.
  EglContext ctx;
  std::string error;
  if (!createSurfacelessContext(&ctx, &error)) {
    std::printf("no GL context (%s): the played frame rates are not measured\n", error.c_str());
  } else {
    {
      VolumeRenderer renderer;
      RenderTarget target;
      if (!renderer.init(&error) ||
          !target.create(1280, 720, RenderTarget::Format::kRgba8, &error)) {
        std::printf("renderer: %s\n", error.c_str());
      } else {
        RenderOptions options;
        options.scale = 0.5f;
        options.moving = true;
        options.finish = true;
        const Light light;
        std::vector<double> sync_ms, render_ms, cpu_ms;
        auto played = [&](const std::function<const Volume&()>& next, std::vector<double>* total) {
          sync_ms.clear();
          render_ms.clear();
          cpu_ms.clear();
          for (int r = 0; r < frames + 1; ++r) {
            const std::clock_t c0 = std::clock();
            const auto t0 = std::chrono::steady_clock::now();
            const Volume& v = next();
            const auto t1 = std::chrono::steady_clock::now();
            renderer.sync(v, light);
            const auto t2 = std::chrono::steady_clock::now();
            renderer.render(view.camera, 1280, 720, target.fbo(), options);
            const auto t3 = std::chrono::steady_clock::now();
            if (r == 0) continue;  // warm-up: textures and the reduced target
            using ms = std::chrono::duration<double, std::milli>;
            total->push_back(ms(t3 - t0).count());
            sync_ms.push_back(ms(t2 - t1).count());
            render_ms.push_back(ms(t3 - t2).count());
            // Process CPU time (llvmpipe's threads included): on an idle 2-core machine a
            // frame takes at least half of it.
            cpu_ms.push_back(1000.0 * double(std::clock() - c0) / CLOCKS_PER_SEC);
          }
        };
        // The painter's path (AnimationPreview on a session holding the picture's cloud): the
        // display copy at half resolution (the default at 256³) and at full resolution; the
        // baseline is the first version (a fresh one-thread frame at full resolution).
        PaintSession session(PaintSessionSettings{1280, 720, a.dims().x}, BrushConfig{},
                             MappingConfig{});
        std::string session_error;
        session.replaceVolume(a, 0, "bench", &session_error);
        const std::string target_path = (dir / "cloudbrush-bench-morph-target.vol").string();
        saveVolume(b, target_path);
        struct Played {
          double ms = 0, sync = 0, render = 0, cpu = 0, apply = 0;
        };
        auto playPreview = [&](bool morph, bool half) {
          AnimationPreview preview;
          preview.setHalfResolution(half);
          if (morph)
            preview.startMorph(session, target_path, 5.0, &session_error);
          else
            preview.toggleWind(session, &session_error);
          std::vector<double> total;
          played(
              [&]() -> const Volume& {
                preview.advance(0.05);
                return preview.shown();
              },
              &total);
          Played result{median(total), median(sync_ms), median(render_ms), median(cpu_ms), 0};
          result.apply = timeMs([&] { preview.fullFrame(session); });
          return result;
        };
        const Played morph_half = playPreview(true, true), morph_full = playPreview(true, false);
        std::vector<double> morph_played_base;
        Volume fresh;
        int k = 0;
        played(
            [&]() -> const Volume& {
              fresh = plan->frameOneThreadReference(0.2f + 0.05f * float(k++));
              return fresh;
            },
            &morph_played_base);
        std::printf(
            "morph played in the painter at 1280x720, scale 0.5, half-resolution copy: %.1f ms "
            "per frame = %.1f fps (sync %.1f, render %.1f; CPU %.1f ms per frame; apply "
            "computes the full frame in %.1f ms); full-resolution copy: %.1f ms = %.1f fps "
            "(sync %.1f, render %.1f); baseline, first version: %.1f ms = %.1f fps; target >= "
            "20 fps\n",
            morph_half.ms, 1000.0 / morph_half.ms, morph_half.sync, morph_half.render,
            morph_half.cpu, morph_half.apply, morph_full.ms, 1000.0 / morph_full.ms,
            morph_full.sync, morph_full.render, median(morph_played_base),
            1000.0 / median(morph_played_base));
        report.figure("morph_played_ms", morph_half.ms);
        report.figure("morph_played_fps", 1000.0 / morph_half.ms);
        report.figure("morph_played_sync_ms", morph_half.sync);
        report.figure("morph_played_render_ms", morph_half.render);
        report.figure("morph_played_cpu_ms", morph_half.cpu);
        report.figure("morph_apply_full_frame_ms", morph_half.apply);
        report.figure("morph_played_full_res_ms", morph_full.ms);
        report.figure("morph_played_full_res_sync_ms", morph_full.sync);
        report.baseline("morph_played_first_version_ms", median(morph_played_base));

        const Played wind_half = playPreview(false, true), wind_full = playPreview(false, false);
        std::vector<double> wind_played_base;
        {
          Volume cloud = a;
          WindSolver solver(cloud.worldMin(), cloud.worldMax());
          solver.setUniformWind({WindRun{}.speed, 0.0f, 0.0f});
          solver.addForce({0.0f, WindRun{}.gust, 0.0f}, glm::vec3(0.0f), 0.5f, 0.1f);
          played(
              [&]() -> const Volume& {
                solver.stepVelocity(kWindStepSeconds);
                solver.advectDensityEveryVoxel(kWindStepSeconds, &cloud);
                return cloud;
              },
              &wind_played_base);
        }
        std::printf(
            "wind played in the painter at 1280x720, scale 0.5, half-resolution copy: %.1f ms "
            "per frame = %.1f fps (sync %.1f, render %.1f; CPU %.1f ms per frame; apply "
            "recomputes its %d steps at full resolution in %.1f ms); full-resolution copy: "
            "%.1f ms = %.1f fps (sync %.1f, render %.1f); baseline, first version: %.1f ms = "
            "%.1f fps; target >= 15 fps\n",
            wind_half.ms, 1000.0 / wind_half.ms, wind_half.sync, wind_half.render, wind_half.cpu,
            frames + 1, wind_half.apply, wind_full.ms, 1000.0 / wind_full.ms, wind_full.sync,
            wind_full.render, median(wind_played_base), 1000.0 / median(wind_played_base));
        report.figure("wind_played_ms", wind_half.ms);
        report.figure("wind_played_fps", 1000.0 / wind_half.ms);
        report.figure("wind_played_sync_ms", wind_half.sync);
        report.figure("wind_played_render_ms", wind_half.render);
        report.figure("wind_played_cpu_ms", wind_half.cpu);
        report.figure("wind_apply_full_frame_ms", wind_half.apply);
        report.figure("wind_played_full_res_ms", wind_full.ms);
        report.figure("wind_played_full_res_sync_ms", wind_full.sync);
        report.baseline("wind_played_first_version_ms", median(wind_played_base));
      }
    }
    destroyGlContext(&ctx);
  }
  report.print();
  return 0;
}

}  // namespace cb
