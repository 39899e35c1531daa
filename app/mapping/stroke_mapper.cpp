#include "app/mapping/stroke_mapper.h"

#include "app/mapping/billows.h"
#include "app/mapping/sheet_mapping.h"

#include <chrono>
#include <cstdio>

namespace cb {
namespace {

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// One branch-free pass. NaN fails every comparison, so every stage treats it as empty; +inf
// is full ink (densities are clamped to 1). Non-finite values fail v·0 == 0.
struct FootprintCounts {
  long long not_finite = 0, non_empty = 0;
};

FootprintCounts countFootprint(const Footprint& f, float empty) {
  FootprintCounts counts;
  for (float v : f.values) {
    counts.not_finite += !(v * 0.0f == 0.0f);
    counts.non_empty += v > empty;
  }
  return counts;
}

// What the edge mapping reads: the footprint's pixels outside the grown circles, their
// spheres, the view and the canvas.
EdgeMappingInput edgeMappingInput(const StrokeResult& stroke, const CircleGrowthResult& growth,
                                  const std::vector<MappedSphere>& spheres,
                                  const PaintViewGeometry& view, glm::vec3 fallback_point,
                                  float max_distance, float empty_threshold) {
  EdgeMappingInput in;
  in.footprint = &stroke.footprint;
  in.covered = &growth.covered;
  in.circles = &growth.circles;
  in.spheres = &spheres;
  in.view = &view;
  in.canvas = stroke.canvas;
  in.fallback_point = fallback_point;
  in.max_distance = max_distance;
  in.stroke_index = stroke.stroke_index;
  in.empty_threshold = empty_threshold;
  return in;
}

}  // namespace

StrokeMapper::StrokeMapper(const MappingConfig& config) : config_(config) {
  validate(config_);
  noise_ = NoiseTexture::shared(config_.noise);
}

void StrokeMapper::warn(MappingReport* report, uint32_t stroke_index,
                        const std::string& text) const {
  std::string line = "mapping: stroke " + std::to_string(stroke_index) + ": " + text;
  if (!quiet_) std::fprintf(stderr, "cloudbrush %s\n", line.c_str());
  report->warnings.push_back(std::move(line));
}

MappingReport StrokeMapper::map(const StrokeResult& stroke, Volume& volume) {
  return map(stroke, volume, config_.method);
}

MappingReport StrokeMapper::map(const StrokeResult& stroke, Volume& volume, MappingMethod method) {
  const auto t_start = std::chrono::steady_clock::now();
  MappingReport report;
  report.method = method;
  const Footprint& f = stroke.footprint;
  const uint32_t id = stroke.stroke_index;
  if (method == MappingMethod::kHybrid) last_circles_.clear();

  if (f.width <= 0 || f.height <= 0 || f.values.size() != size_t(f.width) * size_t(f.height)) {
    warn(&report, id,
         "footprint is malformed (" + std::to_string(f.width) + "x" + std::to_string(f.height) +
             " with " + std::to_string(f.values.size()) + " values); nothing mapped");
    return report;
  }
  const FootprintCounts counts = countFootprint(f, config_.circles.empty_threshold);
  const long long not_finite = counts.not_finite;
  report.non_empty_pixels = counts.non_empty;
  if (not_finite)
    warn(&report, id,
         std::to_string(not_finite) +
             " footprint values are NaN or infinite; NaN is treated as empty, infinity as full "
             "ink");
  if (report.non_empty_pixels == 0) {
    warn(&report, id,
         "footprint has no pixel above the empty threshold " +
             std::to_string(config_.circles.empty_threshold) + "; nothing mapped");
    return report;
  }

  const PaintViewGeometry view(stroke.view.camera, f.width, f.height);
  if (view.nearlyParallelToCanvas())
    warn(&report, id,
         "the paint view is (nearly) parallel to the canvas plane at altitude " +
             std::to_string(stroke.canvas.altitude) +
             "; rays that miss it are placed on the plane facing the camera through the volume "
             "centre");
  const glm::vec3 centre = 0.5f * (volume.worldMin() + volume.worldMax());
  const glm::vec3 fallback_point(centre.x, stroke.canvas.altitude, centre.z);
  const float max_distance =
      glm::length(view.eye() - centre) + glm::length(volume.worldMax() - volume.worldMin());

  VoxelBox dirty;
  if (method == MappingMethod::kSheet) {
    auto t0 = std::chrono::steady_clock::now();
    SheetStats sheet;
    dirty = mapSheet(f, stroke.view.camera, stroke.canvas, config_.sheet, *noise_,
                     config_.circles.empty_threshold, volume, &sheet);
    report.timings.ray_marching_ms = msSince(t0);
    report.covered_pixels = report.non_empty_pixels;
  } else if (method == MappingMethod::kRayMarching) {
    auto t0 = std::chrono::steady_clock::now();
    dirty = mapRayMarching(f, view, stroke.canvas, config_.ray_marching,
                           config_.circles.empty_threshold, volume, &report.ray_marching);
    report.timings.ray_marching_ms = msSince(t0);
    if (report.ray_marching.parallel_pixels)
      warn(&report, id,
           std::to_string(report.ray_marching.parallel_pixels) +
               " pixels' rays are parallel to the canvas or meet it behind the eye; skipped");
  } else {
    auto t0 = std::chrono::steady_clock::now();
    CircleGrowthResult growth = straightforward_growth_
                                    ? growCirclesStraightforward(f, stroke.path, config_.circles)
                                    : growCircles(f, stroke.path, config_.circles);
    report.timings.circle_growth_ms = msSince(t0);
    report.growth_steps = growth.steps;
    report.circle_attempts = growth.attempts;
    if (growth.circles.empty())
      warn(&report, id,
           "no circle of radius >= " + std::to_string(config_.circles.min_radius_px) + " px is " +
               std::to_string(int(config_.circles.accept_white_ratio * 100)) +
               "% white; the whole footprint is edge-mapped onto the canvas");

    t0 = std::chrono::steady_clock::now();
    report.spheres =
        mapCirclesToSpheres(growth.circles, view, stroke.canvas, fallback_point, max_distance);
    billowSpheres(growth.circles, id, config_.spheres, &report.spheres);
    std::vector<MappedSphere> filled = report.spheres;
    for (const MappedSphere& puff : edgePuffs(report.spheres, id, config_.spheres))
      filled.push_back(puff);
    dirty = fillSpheres(filled, *noise_, config_.spheres, volume);
    report.timings.sphere_mapping_ms = msSince(t0);
    long long off_canvas = 0;
    for (const MappedSphere& s : report.spheres) off_canvas += !s.on_canvas;
    if (off_canvas)
      warn(&report, id,
           std::to_string(off_canvas) +
               " circle centres' rays miss the canvas; placed on the "
               "fallback plane");

    t0 = std::chrono::steady_clock::now();
    const EdgeMappingInput in =
        edgeMappingInput(stroke, growth, report.spheres, view, fallback_point, max_distance,
                         config_.circles.empty_threshold);
    dirty = dirty.unite(mapEdges(in, config_.edges, volume, &report.edges));
    report.timings.edge_mapping_ms = msSince(t0);
    if (report.edges.off_canvas_pixels)
      warn(&report, id,
           std::to_string(report.edges.off_canvas_pixels) +
               " edge pixels' rays miss the canvas; placed on the fallback plane");
    if (report.edges.mapped_pixels < report.edges.leftover_pixels)
      warn(&report, id,
           std::to_string(report.edges.leftover_pixels - report.edges.mapped_pixels) +
               " edge pixels fall outside the volume");
    // Every non-empty pixel is either inside a circle or a leftover edge pixel.
    report.covered_pixels = report.non_empty_pixels - report.edges.leftover_pixels;
    report.circles = std::move(growth.circles);
    last_circles_ = report.circles;
  }
  report.dirty = dirty;
  if (!dirty.empty())
    volume.markDirty(dirty);
  else
    warn(&report, id, "the stroke maps outside the volume; nothing changed");
  report.timings.total_ms = msSince(t_start);
  return report;
}

}  // namespace cb
