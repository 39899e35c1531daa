// `cloudbrush bench tools`: picture → cloud (512×512 silhouette into 256³), model → cloud (the
// generated 70,656-triangle torus), morph in-between generation at 256³ and one wind step (64³
// velocity driving the 256³ density), each against a straightforward baseline in the same run;
// then the morph and the wind as the painter plays them (generate + renderer sync + ray cast at
// 1280×720, moving scale 0.5) in the default sky (tools on their window of it) against the
// one-box sky and the first versions. Picture and model times are to the
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
#include "app/cli/args.h"
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
#include "app/volume/sky_extent.h"
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

// What each tool made, rendered by the product's renderer at 640x360 (full resolution, thesis
// style, default light): the picture and its cloud seen from the view it was placed from, the
// model's cloud from there, the morph between them and the wind on the picture's cloud.
void writeToolImages(const std::string& dir, const ImageRgba8& silhouette_image,
                     const Volume& picture_cloud, const Volume& model_cloud, const Camera& camera) {
  constexpr int kW = 640, kH = 360;
  std::filesystem::create_directories(dir);
  VolumeRenderer renderer;
  RenderTarget target;
  std::string error;
  if (!renderer.init(&error) || !target.create(kW, kH, RenderTarget::Format::kRgba8, &error)) {
    std::printf("images: %s\n", error.c_str());
    return;
  }
  const Light light;
  RenderOptions options;
  options.finish = true;
  auto write = [&](const Volume& v, const std::string& name) {
    renderer.sync(v, light);
    renderer.render(camera, kW, kH, target.fbo(), options);
    writePng(dir + "/" + name, target.readRgba8());
    std::printf("wrote %s/%s\n", dir.c_str(), name.c_str());
  };
  writePng(dir + "/tools-picture-input.png", silhouette_image);
  write(picture_cloud, "tools-picture-cloud.png");
  write(model_cloud, "tools-model-cloud.png");
  const CloudMorph morph(picture_cloud, model_cloud);
  for (int k = 0; k <= 4; ++k) {
    char name[64];
    std::snprintf(name, sizeof name, "tools-morph-t%03d.png", 25 * k);
    write(morph.frame(0.25f * float(k)), name);
  }
  WindRun run;
  for (int steps : {0, 15, 30}) {
    run.segments = {{1.0f, 0.0f, steps}};
    Volume blown = picture_cloud;
    blowWind(run, &blown);
    char name[64];
    std::snprintf(name, sizeof name, "tools-wind-%02d-steps.png", steps);
    write(blown, name);
  }
}

}  // namespace

int benchTools(int argc, char** argv) {
  Args args(argc, argv, {"help", "quick"});
  if (args.has("help")) {
    std::printf(
        "usage: cloudbrush bench tools [--quick] [--out-dir DIR]\n"
        "  --quick        one run of each figure instead of three\n"
        "  --out-dir DIR  also write what each tool made, rendered at 640x360 from the view it\n"
        "                 was placed from: the silhouette, its cloud, the model's cloud, the\n"
        "                 morph between them at t = 0, 0.25, 0.5, 0.75, 1 and the wind after 0,\n"
        "                 15 and 30 steps (DIR/tools-*.png)\n");
    return 0;
  }
  const int runs = args.has("quick") ? 1 : 3;
  const std::string out_dir = args.get("out-dir", "");
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
  const double carry_ms = timeMs([&] { CloudMorph again(plan->plan(), a, b); });
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
      std::vector<float> blend(dense_a.size());
      for (size_t i = 0; i < blend.size(); ++i) blend[i] = (1 - t) * dense_a[i] + t * dense_b[i];
      out.assignDense(blend.data());
    }));
  }
  std::printf(
      "morph 256^3: plan and carry %.1f ms (carry alone %.1f; %zu particle pairs, %zu "
      "splats), in-between %.1f ms (baseline, one thread, fresh volume: %.1f ms; per-voxel "
      "cross-fade: %.1f ms)\n",
      plan_ms, carry_ms, plan->pairCount(), plan->splatCount(), median(frame), median(frame_base),
      median(fade));
  report.figure("morph_plan_ms", plan_ms);
  report.figure("morph_carry_ms", carry_ms);
  report.figure("morph_inbetween_ms", median(frame));
  report.figure("morph_pairs", double(plan->pairCount()));
  report.figure("morph_splats", double(plan->splatCount()));
  report.baseline("morph_inbetween_first_version_ms", median(frame_base));
  report.baseline("crossfade_inbetween_ms", median(fade));

  // Wind: a breeze plus an updraft gust on the picture's cloud. A step moves the 64³ velocity
  // and its flow map; the density shown is the start resampled once through the map. Baseline
  // in the same run: the first version, the density itself advected every step (every voxel
  // of its box sampled).
  auto windSolver = [&](const Volume& like) {
    WindSolver wind(like.worldMin(), like.worldMax());
    wind.setUniformWind({0.25f, 0.0f, 0.0f});
    wind.addForce({0.0f, 1.5f, 0.0f}, glm::vec3(0.0f), 0.5f, 0.1f);
    return wind;
  };
  std::vector<double> wind_velocity, wind_map, wind_resample, wind_velocity_base, wind_density_base;
  {
    WindSolver wind = windSolver(a);
    Volume shown = a;
    VoxelBox written = shown.bounds();
    for (int r = 0; r < frames + 1; ++r) {  // the first step faults the scratch grids in
      const double v = timeMs([&] { wind.stepVelocity(kWindStepSeconds); });
      const double m = timeMs([&] { wind.advectFlowMap(kWindStepSeconds); });
      const double d = timeMs([&] { written = wind.resampleDensity(a, &shown, written); });
      if (r == 0) continue;
      wind_velocity.push_back(v);
      wind_map.push_back(m);
      wind_resample.push_back(d);
    }
    WindSolver base = windSolver(a);
    Volume cloud = a;
    for (int r = 0; r < frames + 1; ++r) {
      const double v = timeMs([&] { base.stepVelocity(kWindStepSeconds); });
      const double d = timeMs([&] { base.advectDensityEveryVoxel(kWindStepSeconds, &cloud); });
      if (r == 0) continue;
      wind_velocity_base.push_back(v);
      wind_density_base.push_back(d);
    }
  }
  const double wind_step = median(wind_velocity) + median(wind_map) + median(wind_resample);
  const double wind_step_base = median(wind_velocity_base) + median(wind_density_base);
  std::printf(
      "wind step 64^3 velocity driving 256^3 density: %.1f ms (velocity %.1f, flow map %.1f, "
      "density resampled %.1f; baseline, first version advecting the density every step: "
      "%.1f ms, density %.1f)\n",
      wind_step, median(wind_velocity), median(wind_map), median(wind_resample), wind_step_base,
      median(wind_density_base));
  report.figure("wind_step_ms", wind_step);
  report.figure("wind_velocity_ms", median(wind_velocity));
  report.figure("wind_flow_map_ms", median(wind_map));
  report.figure("wind_density_ms", median(wind_resample));
  report.baseline("wind_step_first_version_ms", wind_step_base);
  report.baseline("wind_density_first_version_ms", median(wind_density_base));

  // A long run recomputed at full resolution (replay; apply needs only the last resampling):
  // 150 steps, 10 s of wind, against the first version's step-by-step advection.
  {
    WindRun run;
    run.segments = {{1.0f, 0.0f, 100}, {0.0f, -1.0f, 50}};
    Volume blown = a, stepwise = a;
    const double replay_ms = timeMs([&] { blowWind(run, &blown); });
    const double stepwise_ms = timeMs([&] { blowWindStepByStep(run, &stepwise); });
    std::printf(
        "wind run of %d steps recomputed at 256^3: %.1f ms (baseline, the density advected "
        "step by step: %.1f ms)\n",
        run.steps(), replay_ms, stepwise_ms);
    report.figure("wind_150_steps_replay_ms", replay_ms);
    report.baseline("wind_150_steps_step_by_step_ms", stepwise_ms);
  }

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
        // The painter's path (AnimationPreview on a session holding the picture's cloud, opened
        // into the home box): the display copy at half resolution (the default for a 256³ home
        // box) and at full resolution, in the default sky (kDefaultSkySpan home boxes across:
        // the tools work on their window of it, tool_window.h) and, as the baseline, in the
        // one-box sky; the first version's baseline is a fresh one-thread frame at full
        // resolution.
        const int grid = a.dims().x;
        PaintSession sky_session(PaintSessionSettings{1280, 720, grid}, BrushConfig{},
                                 MappingConfig{});
        PaintSessionSettings one_box_settings{1280, 720, grid};
        one_box_settings.sky_span = one_box_settings.sky_max_span = kLegacySkySpan;
        PaintSession one_box_session(one_box_settings, BrushConfig{}, MappingConfig{});
        std::string session_error;
        for (PaintSession* s : {&sky_session, &one_box_session})
          if (!s->replaceVolume(a, 0, "bench", &session_error))
            std::printf("open: %s\n", session_error.c_str());
        const std::string target_path = (dir / "cloudbrush-bench-morph-target.vol").string();
        saveVolume(b, target_path);
        struct Played {
          double ms = 0, sync = 0, render = 0, cpu = 0, apply = 0, replay = 0, apply_base = 0;
          glm::ivec3 window{0};
        };
        auto playPreview = [&](PaintSession& session, bool morph, bool half) {
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
          Played result{median(total), median(sync_ms), median(render_ms), median(cpu_ms)};
          result.window = preview.window().dims();
          // Replay recomputes the window's frame from the record (the morph re-planned).
          const UiChange change = preview.change();
          if (morph) {
            const Volume target = loadMorphTarget(target_path, session.volume());
            result.replay = timeMs(
                [&] { morphFrame(session.volume(), target, std::get<ui::ApplyMorph>(change).t); });
          } else {
            const WindRun run = std::get<ui::ApplyWind>(change).run;
            result.replay = timeMs([&] { windFrame(run, session.volume()); });
            if (&session == &one_box_session) {
              Volume stepwise = session.volume();
              result.apply_base = timeMs([&] { blowWindStepByStep(run, &stepwise); });
            }
          }
          // Apply: the full-resolution frame of the window committed (diffed into the cloud,
          // one history step), then undone so the next run starts from the same cloud.
          result.apply = timeMs([&] { preview.apply(&session, 0, &session_error); });
          session.apply(ui::Undo{}, 0, &session_error);
          return result;
        };
        const Played morph_half = playPreview(sky_session, true, true),
                     morph_full = playPreview(sky_session, true, false),
                     morph_one_box = playPreview(one_box_session, true, true);
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
            "morph played in the painter at 1280x720, scale 0.5, in the default sky (window "
            "%dx%dx%d), half-resolution copy: %.1f ms per frame = %.1f fps (sync %.1f, render "
            "%.1f; CPU %.1f ms per frame; apply (full frame of the window + commit) %.1f ms, "
            "replay re-planning %.1f ms); full-resolution copy: %.1f ms = %.1f fps (sync %.1f, "
            "render %.1f); baseline, the one-box sky: %.1f ms = %.1f fps (sync %.1f, render "
            "%.1f; apply %.1f ms, replay %.1f ms); baseline, one-thread fresh frames: %.1f ms = "
            "%.1f fps; target >= 20 fps\n",
            morph_half.window.x, morph_half.window.y, morph_half.window.z, morph_half.ms,
            1000.0 / morph_half.ms, morph_half.sync, morph_half.render, morph_half.cpu,
            morph_half.apply, morph_half.replay, morph_full.ms, 1000.0 / morph_full.ms,
            morph_full.sync, morph_full.render, morph_one_box.ms, 1000.0 / morph_one_box.ms,
            morph_one_box.sync, morph_one_box.render, morph_one_box.apply, morph_one_box.replay,
            median(morph_played_base), 1000.0 / median(morph_played_base));
        report.figure("morph_played_ms", morph_half.ms);
        report.figure("morph_played_fps", 1000.0 / morph_half.ms);
        report.figure("morph_played_sync_ms", morph_half.sync);
        report.figure("morph_played_render_ms", morph_half.render);
        report.figure("morph_played_cpu_ms", morph_half.cpu);
        report.figure("morph_apply_ms", morph_half.apply);
        report.figure("morph_replay_ms", morph_half.replay);
        report.figure("morph_played_full_res_ms", morph_full.ms);
        report.figure("morph_played_full_res_sync_ms", morph_full.sync);
        report.baseline("morph_played_one_box_ms", morph_one_box.ms);
        report.baseline("morph_played_one_box_fps", 1000.0 / morph_one_box.ms);
        report.baseline("morph_played_one_box_sync_ms", morph_one_box.sync);
        report.baseline("morph_apply_one_box_ms", morph_one_box.apply);
        report.baseline("morph_replay_one_box_ms", morph_one_box.replay);
        report.baseline("morph_played_first_version_ms", median(morph_played_base));

        const Played wind_half = playPreview(sky_session, false, true),
                     wind_full = playPreview(sky_session, false, false),
                     wind_one_box = playPreview(one_box_session, false, true);
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
            "wind played in the painter at 1280x720, scale 0.5, in the default sky (window "
            "%dx%dx%d), half-resolution copy: %.1f ms per frame = %.1f fps (sync %.1f, render "
            "%.1f; CPU %.1f ms per frame; apply of its %d steps (the full window resampled "
            "once + commit) %.1f ms, replay with the steps %.1f ms); full-resolution copy: %.1f "
            "ms = %.1f fps (sync %.1f, render %.1f); baseline, the one-box sky: %.1f ms = %.1f "
            "fps (sync %.1f, render %.1f; apply %.1f ms, replay %.1f ms, advecting the full "
            "density step by step %.1f ms); baseline, first version: %.1f ms = %.1f fps; target "
            ">= 15 fps\n",
            wind_half.window.x, wind_half.window.y, wind_half.window.z, wind_half.ms,
            1000.0 / wind_half.ms, wind_half.sync, wind_half.render, wind_half.cpu, frames + 1,
            wind_half.apply, wind_half.replay, wind_full.ms, 1000.0 / wind_full.ms, wind_full.sync,
            wind_full.render, wind_one_box.ms, 1000.0 / wind_one_box.ms, wind_one_box.sync,
            wind_one_box.render, wind_one_box.apply, wind_one_box.replay, wind_one_box.apply_base,
            median(wind_played_base), 1000.0 / median(wind_played_base));
        report.figure("wind_played_ms", wind_half.ms);
        report.figure("wind_played_fps", 1000.0 / wind_half.ms);
        report.figure("wind_played_sync_ms", wind_half.sync);
        report.figure("wind_played_render_ms", wind_half.render);
        report.figure("wind_played_cpu_ms", wind_half.cpu);
        report.figure("wind_apply_ms", wind_half.apply);
        report.figure("wind_replay_ms", wind_half.replay);
        report.figure("wind_played_full_res_ms", wind_full.ms);
        report.figure("wind_played_full_res_sync_ms", wind_full.sync);
        report.baseline("wind_played_one_box_ms", wind_one_box.ms);
        report.baseline("wind_played_one_box_fps", 1000.0 / wind_one_box.ms);
        report.baseline("wind_played_one_box_sync_ms", wind_one_box.sync);
        report.baseline("wind_apply_one_box_ms", wind_one_box.apply);
        report.baseline("wind_replay_one_box_ms", wind_one_box.replay);
        report.baseline("wind_apply_step_by_step_ms", wind_one_box.apply_base);
        report.baseline("wind_played_first_version_ms", median(wind_played_base));
      }
    }
    if (!out_dir.empty()) writeToolImages(out_dir, image, a, b, view.camera);
    destroyGlContext(&ctx);
  }
  report.print();
  return 0;
}

}  // namespace cb
