// What the painter's animations (morphing and wind "live in the painter") need so that
// a committed frame can be recomputed from its journal record: the morph target by name, and a
// wind run as its settings and step counts. The painter animates a copy of the session's cloud
// with these; "apply" journals the record, and replay recomputes the same bytes from it.
//
// In a sky wider than one box, morph and wind work on a window of it (tool_window.h): the frame
// they make is the window's (`WindowFrame`), pasted back where it was cropped from.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "app/tools/tool_window.h"
#include "app/tools/wind.h"
#include "app/volume/volume.h"

namespace cb {

// The morph target named `source`: "bundled:SEED" is the bundled cumulus
// (app/volume/scene_generators.h) on `like`'s grid; anything else is a saved cloud's path
// (app/volume/volume_file.h). ToolError kMismatchedVolumes when it does not fit `like`'s grid
// and world box; the loader's error when the file cannot be read.
Volume loadMorphTarget(const std::string& source, const Volume& like);

// The display copy of an animation: half the resolution on each axis (each voxel the mean of
// its 2×2×2, the last voxel of an odd dimension alone), the same world box, so it is one eighth
// of the voxels to animate, upload and light. Only the bricks under allocated ones are computed
// (the cost follows the cloud, not the sky); in parallel, the same bytes on any thread count.
Volume halfResolution(const Volume& volume);

// A tool's result on its window: the window's voxels (over the window's world box), to be put
// back at `at` in the volume it was cropped from (pasteVolume).
struct WindowFrame {
  Volume volume;
  glm::ivec3 at{0};
};
// `cloud` with `frame` pasted in: what committing the frame makes of the cloud.
Volume withFrame(const Volume& cloud, const WindowFrame& frame);

// One stretch of wind: blowing horizontally towards (dx, dz) for `steps` steps.
struct WindSegment {
  float dx = 1.0f, dz = 0.0f;
  int steps = 0;
};
// A wind run: its speed (world units per second), the updraft gust given at the start of each
// segment (Eq. 3.5, a force falling off from the sky box's centre), and its segments in order.
// Every step advances kWindStepSeconds, whatever the frame rate, so the step count is the time.
struct WindRun {
  float speed = 0.25f;
  float gust = 1.5f;
  std::vector<WindSegment> segments;
  int steps() const;
};
constexpr float kWindStepSeconds = 1.0f / 15.0f;

// The wind animation: a WindSolver over a window's world box (64³ over a whole volume, 64 cells
// per home box over a window of a wider sky), stepped one step at a time; the density it shows
// is the starting cloud carried by the solver's flow map (wind.h).
class WindAnimation {
 public:
  // Over the whole of `like` (64³ cells, the gust a quarter of its width across).
  WindAnimation(const Volume& like, float speed, float gust);
  // Over `window` (its world box, wind cells and gust radius).
  WindAnimation(const ToolWindow& window, float speed, float gust);
  // Turns the wind towards (dx, dz) from the next step (a new segment; the velocity field
  // becomes the uniform wind plus the gust again).
  void setDirection(float dx, float dz);
  // One step of kWindStepSeconds (velocity and flow map; no voxel is touched).
  void step();
  // The cloud after the steps so far: `start` (the cloud when the wind started, at any
  // resolution over the same world box) carried into `out`; WindSolver::resampleDensity.
  VoxelBox show(const Volume& start, Volume* out, const VoxelBox& previous) const;
  const WindSolver& solver() const { return solver_; }
  // One step the way journal specification 1.1 recorded wind: the velocity step, then the
  // density itself advected (WindSolver::advectDensityEveryVoxel).
  void stepDensityItself(Volume* density);
  const WindRun& run() const { return run_; }

 private:
  void blow();
  WindSolver solver_;
  glm::vec3 centre_;
  float gust_radius_;  // 0: a quarter of the solver's width
  WindRun run_;
};

// Recomputes a recorded run on `density` (replay and apply): the steps on the coarse grid over
// the density's window (toolWindow), then one resampling of the window; the same bytes as the
// animation shows at that resolution. windFrame returns the window's frame, blowWind pastes it.
WindowFrame windFrame(const WindRun& run, const Volume& density);
void blowWind(const WindRun& run, Volume* density);
// The morph of `source` into `target` (the same dims and world box) at t, on the window of
// their content (toolWindow of source ∪ target): CloudMorph(window of source, window of target).
WindowFrame morphFrame(const Volume& source, const Volume& target, float t);
// A run recorded by journal specification 1.1 (`wind=`), recomputed as it was then: each step
// advecting the density itself (over the whole volume: such records come from one-box skies).
void blowWindStepByStep(const WindRun& run, Volume* density);

}  // namespace cb
