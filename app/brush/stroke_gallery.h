// The stroke gallery: twelve canonical strokes with pen-like pressure and tilt, generated
// reproducibly on a screen of any size, for the acceptance test of what a painted cloud looks
// like (tests/unit/mapping/stroke_gallery_test.cpp) and `cloudbrush bench strokes`. The first
// five are the calligraphic strokes the thesis's brushes were built for (dot, horizontal,
// bending, S-curve, hook; thesis §5.1, Fig. 5.1's 永); then a scribble, a fast flick, a slow
// press, a light touch, a tilted side stroke, the mouse at its fixed pressure and a dab.
// Positions are screen pixels (centred on the screen, sized from its height); a tablet's reports
// come at 200 Hz, the mouse's at 125 Hz.
#pragma once

#include <string>
#include <vector>

#include "app/brush/brush_input.h"

namespace cb {

struct GalleryStroke {
  std::string name;
  std::vector<BrushInput> samples;  // footprint_px in screen pixels; t_ns from 0
  bool point_like = false;          // a dot or dab: measured around its centre, not along it
};

std::vector<GalleryStroke> strokeGallery(int screen_width, int screen_height);

// The samples scaled to a footprint `scale` footprint pixels per screen pixel (per axis).
std::vector<BrushInput> scaledSamples(const std::vector<BrushInput>& samples, glm::vec2 scale);

}  // namespace cb
