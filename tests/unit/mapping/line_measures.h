// How a line-drawn style's lines hold on a rendered cloud, beyond speckle (speckle.h):
//  - outline breaks: the share of the cloud's silhouette (its boundary against the empty image)
//    with no dark line pixel of the style's image near it — a dashed outline leaves long
//    stretches of bare edge;
//  - solid patches: the share of the cloud's pixels inside a solid area of line tone (every pixel
//    of a square window dark) — hatching and lines always leave paper between them, a grey or
//    black blotch does not.
#pragma once

#include "app/render/image_io.h"

namespace cb::test {

struct OutlineBreaks {
  long edge = 0;    // silhouette pixels: cloud pixels with a 4-neighbour outside the cloud
  long broken = 0;  // of those, with no dark pixel within `reach` pixels (Chebyshev)
  double fraction() const { return edge ? double(broken) / double(edge) : 0.0; }
};

// The silhouette is that of `extent` against `extent_empty` (a pixel is cloud where they differ,
// as in speckle.h): an image of the same view in a style whose every tone differs from its
// background (the cartoon's; the ink's lit wash is bare paper, so its own image has edges inside
// the cloud). A pixel of `image` (same size) is dark below `dark_luminance` (0..1, Rec. 709).
OutlineBreaks measureOutlineBreaks(const ImageRgba8& image, const ImageRgba8& extent,
                                   const ImageRgba8& extent_empty, float dark_luminance, int reach);

struct SolidPatches {
  long cloud = 0;  // pixels inside the silhouette (extent against extent_empty)
  long solid = 0;  // of those, pixels of `image` whose (2·radius + 1)² window is all below
                   // dark_luminance
  double fraction() const { return cloud ? double(solid) / double(cloud) : 0.0; }
};

// `extent` and `extent_empty` as for measureOutlineBreaks; `image` the style's image.
SolidPatches measureSolidPatches(const ImageRgba8& image, const ImageRgba8& extent,
                                 const ImageRgba8& extent_empty, float dark_luminance, int radius);

}  // namespace cb::test
