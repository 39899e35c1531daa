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
#include "app/shell/painter/animation_preview.h"
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

// What the parts of the bench share: the view the tools place from, runs per figure, the report.
struct ToolsBench {
  explicit ToolsBench(BenchReport& r) : report(r) {}
  BenchReport& report;
  ToolView view;
  int runs = 3;
  int frames = 6;  // in-betweens and wind steps timed
  std::filesystem::path dir;
};

// Picture → cloud, against the naive uniform depth on one thread.
void benchPicture(ToolsBench& t, const std::string& png) {
  std::vector<double> picture, picture_base;
  for (int r = 0; r < t.runs; ++r) {
    Volume volume;
    picture.push_back(timeMs([&] { pictureToCloud(png, t.view, PictureCloudParams{}, &volume); }));
    Volume base;
    PictureCloudParams naive;
    naive.naive_uniform_depth = true;
    setWorkerThreads(1);
    picture_base.push_back(timeMs([&] { pictureToCloud(png, t.view, naive, &base); }));
    setWorkerThreads(0);
  }
  std::printf(
      "picture -> cloud 512x512 into 256^3: %.1f ms (baseline, naive uniform depth, one "
      "thread: %.1f ms; target <= 300)\n",
      median(picture), median(picture_base));
  t.report.figure("picture_to_volume_ms", median(picture));
  t.report.baseline("picture_naive_one_thread_ms", median(picture_base));
}

// Model → cloud, against one thread.
void benchModel(ToolsBench& t, const std::string& obj, size_t triangles) {
  std::vector<double> model, model_base;
  for (int r = 0; r < t.runs; ++r) {
    Volume volume;
    model.push_back(timeMs([&] { modelToCloud(obj, t.view, ModelCloudParams{}, &volume); }));
    Volume base;
    setWorkerThreads(1);
    model_base.push_back(timeMs([&] { modelToCloud(obj, t.view, ModelCloudParams{}, &base); }));
    setWorkerThreads(0);
  }
  std::printf(
      "model -> cloud %zu triangles into 256^3 (load + check + voxelise): %.1f ms "
      "(baseline, one thread: %.1f ms; target <= 500)\n",
      triangles, median(model), median(model_base));
  t.report.figure("model_to_volume_ms", median(model));
  t.report.figure("model_triangles", double(triangles));
  t.report.baseline("model_one_thread_ms", median(model_base));
}

// The morph's plan, carry and in-between alone, against the first version (the one-thread
// scatter into a fresh volume per frame) and a per-voxel cross-fade. Returns the plan.
std::unique_ptr<CloudMorph> benchMorph(ToolsBench& t, const Volume& a, const Volume& b) {
  std::unique_ptr<CloudMorph> plan;
  const double plan_ms = timeMs([&] { plan = std::make_unique<CloudMorph>(a, b); });
  const double carry_ms = timeMs([&] { CloudMorph again(plan->plan(), a, b); });
  std::vector<double> frame, frame_base, fade;
  const std::vector<float> dense_a = a.toDense(), dense_b = b.toDense();  // the cross-fade's grids
  Volume shown = a;
  VoxelBox written = shown.bounds();
  for (int r = 0; r < t.frames; ++r) {
    const float f = 0.2f + 0.1f * float(r);
    frame.push_back(timeMs([&] { written = plan->frameInto(f, &shown, written); }));
    frame_base.push_back(timeMs([&] { plan->frameOneThreadReference(f); }));
    fade.push_back(timeMs([&] {
      Volume out(a.dims());
      std::vector<float> blend(dense_a.size());
      for (size_t i = 0; i < blend.size(); ++i) blend[i] = (1 - f) * dense_a[i] + f * dense_b[i];
      out.assignDense(blend.data());
    }));
  }
  std::printf(
      "morph 256^3: plan and carry %.1f ms (carry alone %.1f; %zu particle pairs, %zu "
      "splats), in-between %.1f ms (baseline, one thread, fresh volume: %.1f ms; per-voxel "
      "cross-fade: %.1f ms)\n",
      plan_ms, carry_ms, plan->pairCount(), plan->splatCount(), median(frame), median(frame_base),
      median(fade));
  t.report.figure("morph_plan_ms", plan_ms);
  t.report.figure("morph_carry_ms", carry_ms);
  t.report.figure("morph_inbetween_ms", median(frame));
  t.report.figure("morph_pairs", double(plan->pairCount()));
  t.report.figure("morph_splats", double(plan->splatCount()));
  t.report.baseline("morph_inbetween_first_version_ms", median(frame_base));
  t.report.baseline("crossfade_inbetween_ms", median(fade));
  return plan;
}

// Wind: a breeze plus an updraft gust on the picture's cloud. A step moves the 64³ velocity and
// its flow map; the density shown is the start resampled once through the map. Baseline in the
// same run: the first version, the density itself advected every step (every voxel of its box
// sampled). Then a long run recomputed at full resolution (replay; apply needs only the last
// resampling): 150 steps, 10 s of wind, against the step-by-step advection.
void benchWind(ToolsBench& t, const Volume& a) {
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
    for (int r = 0; r < t.frames + 1; ++r) {  // the first step faults the scratch grids in
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
    for (int r = 0; r < t.frames + 1; ++r) {
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
  t.report.figure("wind_step_ms", wind_step);
  t.report.figure("wind_velocity_ms", median(wind_velocity));
  t.report.figure("wind_flow_map_ms", median(wind_map));
  t.report.figure("wind_density_ms", median(wind_resample));
  t.report.baseline("wind_step_first_version_ms", wind_step_base);
  t.report.baseline("wind_density_first_version_ms", median(wind_density_base));

  WindRun run;
  run.segments = {{1.0f, 0.0f, 100}, {0.0f, -1.0f, 50}};
  Volume blown = a, stepwise = a;
  const double replay_ms = timeMs([&] { blowWind(run, &blown); });
  const double stepwise_ms = timeMs([&] { blowWindStepByStep(run, &stepwise); });
  std::printf(
      "wind run of %d steps recomputed at 256^3: %.1f ms (baseline, the density advected "
      "step by step: %.1f ms)\n",
      run.steps(), replay_ms, stepwise_ms);
  t.report.figure("wind_150_steps_replay_ms", replay_ms);
  t.report.baseline("wind_150_steps_step_by_step_ms", stepwise_ms);
}

// One way of playing a tool in the painter, per frame (medians).
struct Played {
  double ms = 0, sync = 0, render = 0, cpu = 0, apply = 0, replay = 0, apply_base = 0;
  glm::ivec3 window{0};
};

// The morph and the wind as the painter plays them: generate + sync + render at 1280x720,
// moving scale 0.5.
class PlayedBench {
 public:
  PlayedBench(ToolsBench& t, VolumeRenderer& renderer, RenderTarget& target)
      : t_(t), renderer_(renderer), target_(target) {
    options_.scale = 0.5f;
    options_.moving = true;
    options_.finish = true;
  }

  // frames + 1 frames of next() synced and rendered (the first a warm-up: textures and the
  // reduced target): each one's total into *total, the parts into sync_ms_, render_ms_, cpu_ms_.
  void played(const std::function<const Volume&()>& next, std::vector<double>* total) {
    sync_ms_.clear();
    render_ms_.clear();
    cpu_ms_.clear();
    for (int r = 0; r < t_.frames + 1; ++r) {
      const std::clock_t c0 = std::clock();
      const auto t0 = std::chrono::steady_clock::now();
      const Volume& v = next();
      const auto t1 = std::chrono::steady_clock::now();
      renderer_.sync(v, light_);
      const auto t2 = std::chrono::steady_clock::now();
      renderer_.render(t_.view.camera, 1280, 720, target_.fbo(), options_);
      const auto t3 = std::chrono::steady_clock::now();
      if (r == 0) continue;
      using ms = std::chrono::duration<double, std::milli>;
      total->push_back(ms(t3 - t0).count());
      sync_ms_.push_back(ms(t2 - t1).count());
      render_ms_.push_back(ms(t3 - t2).count());
      // Process CPU time (llvmpipe's threads included): on an idle 2-core machine a frame
      // takes at least half of it.
      cpu_ms_.push_back(1000.0 * double(std::clock() - c0) / CLOCKS_PER_SEC);
    }
  }

  // The painter's path: AnimationPreview on `session` (a morph towards target_path, or the
  // wind), its display copy at half or full resolution; then the replay of its record and the
  // apply (the full-resolution frame of the window committed, then undone so the next run
  // starts from the same cloud). `one_box`: also times the wind advected step by step.
  Played playPreview(PaintSession& session, const std::string& target_path, bool morph, bool half,
                     bool one_box) {
    std::string error;
    AnimationPreview preview;
    preview.setHalfResolution(half);
    if (morph)
      preview.startMorph(session, target_path, 5.0, &error);
    else
      preview.toggleWind(session, &error);
    std::vector<double> total;
    played(
        [&]() -> const Volume& {
          preview.advance(0.05);
          return preview.shown();
        },
        &total);
    Played result{median(total), median(sync_ms_), median(render_ms_), median(cpu_ms_)};
    result.window = preview.window().dims();
    // Replay recomputes the window's frame from the record (the morph re-planned).
    const UiChange change = preview.change();
    if (morph) {
      const Volume target = loadMorphTarget(target_path, session.volume());
      result.replay =
          timeMs([&] { morphFrame(session.volume(), target, std::get<ui::ApplyMorph>(change).t); });
    } else {
      const WindRun run = std::get<ui::ApplyWind>(change).run;
      result.replay = timeMs([&] { windFrame(run, session.volume()); });
      if (one_box) {
        Volume stepwise = session.volume();
        result.apply_base = timeMs([&] { blowWindStepByStep(run, &stepwise); });
      }
    }
    result.apply = timeMs([&] { preview.apply(&session, 0, &error); });
    session.apply(ui::Undo{}, 0, &error);
    return result;
  }

 private:
  ToolsBench& t_;
  VolumeRenderer& renderer_;
  RenderTarget& target_;
  RenderOptions options_;
  const Light light_;
  std::vector<double> sync_ms_, render_ms_, cpu_ms_;
};

// The figures of one tool played: in the default sky at half resolution (the figures), at full
// resolution, and in the one-box sky (baselines).
void reportPlayed(BenchReport& report, const char* tool, const Played& half, const Played& full,
                  const Played& one_box) {
  const std::string p = tool;
  report.figure(p + "_played_ms", half.ms);
  report.figure(p + "_played_fps", 1000.0 / half.ms);
  report.figure(p + "_played_sync_ms", half.sync);
  report.figure(p + "_played_render_ms", half.render);
  report.figure(p + "_played_cpu_ms", half.cpu);
  report.figure(p + "_apply_ms", half.apply);
  report.figure(p + "_replay_ms", half.replay);
  report.figure(p + "_played_full_res_ms", full.ms);
  report.figure(p + "_played_full_res_sync_ms", full.sync);
  report.baseline(p + "_played_one_box_ms", one_box.ms);
  report.baseline(p + "_played_one_box_fps", 1000.0 / one_box.ms);
  report.baseline(p + "_played_one_box_sync_ms", one_box.sync);
  report.baseline(p + "_apply_one_box_ms", one_box.apply);
  report.baseline(p + "_replay_one_box_ms", one_box.replay);
}

// The morph between the picture's cloud `a` and the model's cloud `b`, played.
void benchMorphPlayed(ToolsBench& t, PlayedBench& bench, PaintSession& sky_session,
                      PaintSession& one_box_session, const std::string& target_path,
                      const CloudMorph& plan) {
  const Played half = bench.playPreview(sky_session, target_path, true, true, false),
               full = bench.playPreview(sky_session, target_path, true, false, false),
               one_box = bench.playPreview(one_box_session, target_path, true, true, true);
  std::vector<double> base;
  Volume fresh;
  int k = 0;
  bench.played(
      [&]() -> const Volume& {
        fresh = plan.frameOneThreadReference(0.2f + 0.05f * float(k++));
        return fresh;
      },
      &base);
  std::printf(
      "morph played in the painter at 1280x720, scale 0.5, in the default sky (window "
      "%dx%dx%d), half-resolution copy: %.1f ms per frame = %.1f fps (sync %.1f, render "
      "%.1f; CPU %.1f ms per frame; apply (full frame of the window + commit) %.1f ms, "
      "replay re-planning %.1f ms); full-resolution copy: %.1f ms = %.1f fps (sync %.1f, "
      "render %.1f); baseline, the one-box sky: %.1f ms = %.1f fps (sync %.1f, render "
      "%.1f; apply %.1f ms, replay %.1f ms); baseline, one-thread fresh frames: %.1f ms = "
      "%.1f fps; target >= 20 fps\n",
      half.window.x, half.window.y, half.window.z, half.ms, 1000.0 / half.ms, half.sync,
      half.render, half.cpu, half.apply, half.replay, full.ms, 1000.0 / full.ms, full.sync,
      full.render, one_box.ms, 1000.0 / one_box.ms, one_box.sync, one_box.render, one_box.apply,
      one_box.replay, median(base), 1000.0 / median(base));
  reportPlayed(t.report, "morph", half, full, one_box);
  t.report.baseline("morph_played_first_version_ms", median(base));
}

// The wind on the picture's cloud `a`, played.
void benchWindPlayed(ToolsBench& t, PlayedBench& bench, PaintSession& sky_session,
                     PaintSession& one_box_session, const std::string& target_path,
                     const Volume& a) {
  const Played half = bench.playPreview(sky_session, target_path, false, true, false),
               full = bench.playPreview(sky_session, target_path, false, false, false),
               one_box = bench.playPreview(one_box_session, target_path, false, true, true);
  std::vector<double> base;
  Volume cloud = a;
  WindSolver solver(cloud.worldMin(), cloud.worldMax());
  solver.setUniformWind({WindRun{}.speed, 0.0f, 0.0f});
  solver.addForce({0.0f, WindRun{}.gust, 0.0f}, glm::vec3(0.0f), 0.5f, 0.1f);
  bench.played(
      [&]() -> const Volume& {
        solver.stepVelocity(kWindStepSeconds);
        solver.advectDensityEveryVoxel(kWindStepSeconds, &cloud);
        return cloud;
      },
      &base);
  std::printf(
      "wind played in the painter at 1280x720, scale 0.5, in the default sky (window "
      "%dx%dx%d), half-resolution copy: %.1f ms per frame = %.1f fps (sync %.1f, render "
      "%.1f; CPU %.1f ms per frame; apply of its %d steps (the full window resampled "
      "once + commit) %.1f ms, replay with the steps %.1f ms); full-resolution copy: %.1f "
      "ms = %.1f fps (sync %.1f, render %.1f); baseline, the one-box sky: %.1f ms = %.1f "
      "fps (sync %.1f, render %.1f; apply %.1f ms, replay %.1f ms, advecting the full "
      "density step by step %.1f ms); baseline, first version: %.1f ms = %.1f fps; target "
      ">= 15 fps\n",
      half.window.x, half.window.y, half.window.z, half.ms, 1000.0 / half.ms, half.sync,
      half.render, half.cpu, t.frames + 1, half.apply, half.replay, full.ms, 1000.0 / full.ms,
      full.sync, full.render, one_box.ms, 1000.0 / one_box.ms, one_box.sync, one_box.render,
      one_box.apply, one_box.replay, one_box.apply_base, median(base), 1000.0 / median(base));
  reportPlayed(t.report, "wind", half, full, one_box);
  t.report.baseline("wind_apply_step_by_step_ms", one_box.apply_base);
  t.report.baseline("wind_played_first_version_ms", median(base));
}

// The painter's sessions holding the picture's cloud `a`, opened into the home box: in the
// default sky (kDefaultSkySpan home boxes across: the tools work on their window of it,
// tool_window.h) and, as the baseline, in the one-box sky. The display copy is played at half
// resolution (the default for a 256³ home box) and at full resolution; the first version's
// baseline is a fresh one-thread frame at full resolution.
void benchPlayedTools(ToolsBench& t, const Volume& a, const Volume& b, const CloudMorph& plan) {
  VolumeRenderer renderer;
  RenderTarget target;
  std::string error;
  if (!renderer.init(&error) || !target.create(1280, 720, RenderTarget::Format::kRgba8, &error)) {
    std::printf("renderer: %s\n", error.c_str());
    return;
  }
  const int grid = a.dims().x;
  PaintSession sky_session(PaintSessionSettings{1280, 720, grid}, BrushConfig{}, MappingConfig{});
  PaintSessionSettings one_box_settings{1280, 720, grid};
  one_box_settings.sky_span = one_box_settings.sky_max_span = kLegacySkySpan;
  PaintSession one_box_session(one_box_settings, BrushConfig{}, MappingConfig{});
  for (PaintSession* s : {&sky_session, &one_box_session})
    if (!s->replaceVolume(a, 0, "bench", &error)) std::printf("open: %s\n", error.c_str());
  const std::string target_path = (t.dir / "cloudbrush-bench-morph-target.vol").string();
  saveVolume(b, target_path);
  PlayedBench bench(t, renderer, target);
  benchMorphPlayed(t, bench, sky_session, one_box_session, target_path, plan);
  benchWindPlayed(t, bench, sky_session, one_box_session, target_path, a);
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
  BenchReport report("tools");
  ToolsBench t(report);
  t.runs = args.has("quick") ? 1 : 3;
  t.frames = t.runs == 1 ? 3 : 6;
  t.dir = std::filesystem::temp_directory_path();
  t.view.camera = Camera::reference();
  const std::string out_dir = args.get("out-dir", "");

  ImageRgba8 image;
  image.width = image.height = 512;
  image.pixels = silhouette(512, 512);
  const std::string png = (t.dir / "cloudbrush-bench-silhouette.png").string();
  writePng(png, image);
  benchPicture(t, png);
  const TriangleMesh torus = makeDisplacedTorus(0.6f, 0.25f, 0.2f, 192, 184);
  const std::string obj = (t.dir / "cloudbrush-bench-torus.obj").string();
  writeObj(obj, torus);
  benchModel(t, obj, torus.triangles.size());

  // Morph between the picture's cloud and the model's cloud, and wind on the picture's cloud:
  // the in-between / step alone, then as the painter plays them — generated, synced to the
  // renderer (upload, occupancy, light) and ray cast at 1280x720, moving scale 0.5.
  Volume a, b;
  pictureToCloud(png, t.view, PictureCloudParams{}, &a);
  modelToCloud(obj, t.view, ModelCloudParams{}, &b);
  const std::unique_ptr<CloudMorph> plan = benchMorph(t, a, b);
  benchWind(t, a);

  EglContext ctx;
  std::string error;
  if (!createSurfacelessContext(&ctx, &error)) {
    std::printf("no GL context (%s): the played frame rates are not measured\n", error.c_str());
  } else {
    benchPlayedTools(t, a, b, *plan);
    if (!out_dir.empty()) writeToolImages(out_dir, image, a, b, t.view.camera);
    destroyGlContext(&ctx);
  }
  report.print();
  return 0;
}

}  // namespace cb
