// The sky's extent ("A sky without walls"). The thesis's sky is one box of grid³ voxels
// over the world box [-1,1]³ (§3.3; "limited to 256³", §8.1). The painter's sky keeps that box
// and its voxel size as the home box, at the centre of a wider extent: `span` home boxes across
// in x and in z (one high), so the canvas reaches past the old walls and a stroke lands wherever
// it is drawn. The sparse volume costs memory only where cloud is painted, so a wide extent is
// cheap until it is used.
//
//   span 1: the old box, grid × grid × grid over [-1,1]³ (journals recorded before the sky grew)
//   span 4: the default, 1024 × 256 × 1024 voxels over [-4,4] × [-1,1] × [-4,4] for grid 256
//   span 8: the widest for grid 256, 2048 × 256 × 2048 (kMaxVolumeDim across)
//
// The sky grows with what is painted: a session widens it, a span at a time as needed, before a
// stroke that reaches past its edge (skyToHold, growSky), keeping every voxel where it is in the
// world, so the home box stays on [-1,1]³ and the sun (a direction) lights the cloud as before.
#pragma once

#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "app/volume/volume.h"

namespace cb {

// Home boxes across the sky in x and z for a new session (config-free: journals record theirs).
constexpr int kDefaultSkySpan = 4;
// A Session record without a sky span was made when the sky was one box.
constexpr int kLegacySkySpan = 1;
constexpr int kMaxSkySpan = 8;

struct SkyExtent {
  int grid = 256;              // voxels along each axis of the home box
  int span = kDefaultSkySpan;  // home boxes across in x and z

  glm::ivec3 dims() const { return {span * grid, grid, span * grid}; }
  glm::vec3 worldMin() const { return {-float(span), -1.0f, -float(span)}; }
  glm::vec3 worldMax() const { return {float(span), 1.0f, float(span)}; }
  // The home box's first voxel in the sky's grid (its world box is [-1,1]³).
  glm::ivec3 homeOffset() const { return {(span - 1) * grid / 2, 0, (span - 1) * grid / 2}; }
  // An empty error when grid and span make a sky of at most kMaxVolumeDim voxels per axis and
  // the home box sits on whole voxels; otherwise what is wrong, in words.
  std::string check() const;
};

// The widest sky of this grid the limits allow, at most `max_span` home boxes across: the span
// checks pass (kMaxVolumeDim, whole voxels) and, when it is wider than `span`, every span
// between them moves the home box by whole volume bricks, so growing re-places bricks rather
// than voxels and the history's brick deltas follow (grid a multiple of 32; otherwise the sky
// cannot grow and this is `span`).
int widestSkySpan(int grid, int span, int max_span);

// The narrowest sky at least as wide as `from` and at most `max_span` across (widestSkySpan)
// holding the world-space x/z rectangle [xz_min, xz_max]; the widest one when none holds it.
SkyExtent skyToHold(const SkyExtent& from, int max_span, glm::vec2 xz_min, glm::vec2 xz_max);

// Where an edit can write, in world x/z, known before it writes: a finished stroke's
// (app/mapping/stroke_reach.h) or a placed picture's or model's (app/tools/tool_view.h
// `placementReach`). The session grows the sky to hold it first.
struct SkyReach {
  bool inked = false;                    // the edit writes something at all
  bool bounded = false;                  // the rectangle is known (else the edit may land anywhere)
  glm::vec2 xz_min{0.0f}, xz_max{0.0f};  // world x/z rectangle (valid when inked and bounded)
};

// The sky an edit of this reach needs: `from` when it writes nothing, the widest (as skyToHold
// with no rectangle) when its rectangle is unknown, else skyToHold of its rectangle.
SkyExtent skyToHold(const SkyExtent& from, int max_span, const SkyReach& reach);

// `sky` (a sky of extent `from`) grown to the wider extent `to` around it: the same grid,
// every brick moved to where it was in the world (the home box stays on [-1,1]³), the rest
// empty; `sky` is left empty. std::invalid_argument when `to` is not a wider sky of the same
// grid that `from` grows into by whole bricks.
Volume growSky(Volume&& sky, const SkyExtent& from, const SkyExtent& to);
// Where `from`'s voxel 0 lies in the grown sky `to` (whole bricks of Volume::kBrickSize).
glm::ivec3 growthOffset(const SkyExtent& from, const SkyExtent& to);

// The extent `volume` was made with, when it is a sky (span home boxes across, y one box high over
// [-1,1]); std::nullopt for any other volume (a file from elsewhere, a test shape).
std::optional<SkyExtent> skyExtentOf(const Volume& volume);

// An empty sky of this extent.
Volume makeSkyVolume(const SkyExtent& extent);

// True when `volume` is a cloud of the one-box sky that fits `extent`'s home box: grid³ voxels
// over [-1,1]³ (a cloud saved before the sky grew, the bundled cumulus).
bool isHomeBoxCloud(const Volume& volume, const SkyExtent& extent);

// `home` (a grid³ volume over [-1,1]³, such as the bundled cumulus) placed in the home box of an
// otherwise empty sky of `extent`; home.dims() must be extent.grid³ (std::invalid_argument).
Volume placeInSky(const Volume& home, const SkyExtent& extent);

}  // namespace cb
