// The reprojected orbit (app/render/temporal_reprojection.h) beside the half-resolution orbit it
// replaces, measured in one process frame block by frame block (the machine is shared: the two
// alternate, so a change in load weighs on both), for `cloudbrush bench scale`.
#pragma once

#include <string>

#include "app/render/volume_renderer.h"
#include "app/scene/camera.h"

namespace cb {

struct ReprojectedOrbitFigures {
  int factor = 0;  // one pixel in factor² cast
  // Per frame, median over the blocks: wall time to glFinish, and process CPU (all threads).
  double ms = -1, cpu_ms = -1;
  double base_ms = -1, base_cpu_ms = -1;  // the half-resolution orbit (scale 0.5, step 2)
  // The reprojected frame's parts, wall time to a glFinish each (median): the 1/f cast, the
  // reprojection pass, the copy into the target (ReprojectionStats).
  double cast_ms = -1, reproject_ms = -1, copy_ms = -1;
  // Per-pixel difference from a full cast of the same camera (largest channel, of 255): mean
  // and 99th percentile over the measured frames.
  double error_mean = -1, error_p99 = -1;
  double base_error_mean = -1, base_error_p99 = -1;
  // The orbit as the painter casts most of its moving frames: at the volume's detail
  // (volume_detail.h; the moving scale ½ asked), its scale, timing and error alike.
  double detail_scale = -1, detail_ms = -1, detail_cpu_ms = -1;
  double detail_error_mean = -1, detail_error_p99 = -1;
};

// An orbit of `view` by 3° a frame at width×height, `blocks` blocks of 8 frames each way (the
// half-resolution, the detail and the reprojected orbit), with the renderer's current volume. With
// `shots_dir`, writes a few reprojected frames, the full cast and the half-resolution frame of the
// same camera there (PNG).
ReprojectedOrbitFigures measureReprojectedOrbit(VolumeRenderer& renderer, const Camera& view,
                                                int width, int height, int factor, int blocks,
                                                const std::string& shots_dir);

}  // namespace cb
