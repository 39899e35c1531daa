// Area mapping: which part of the tablet drives which part of the screen. Produces one
// homogeneous 3x3 transform from tablet millimetres (origin at the active area's top-left,
// y towards the user) to screen pixels (origin top-left, y down).
//
// Steps: take the tablet area (the whole active area or a custom rectangle), turn it by the
// rotation (the angle the tablet is physically turned clockwise on the desk; 90° steps and
// arbitrary angles), take the largest centred axis-aligned rectangle of the wanted aspect
// inside the turned area, and map that rectangle onto the screen region.
//   stretch    whole area -> whole region (aspect may change)
//   fit        aspect-preserving: the tablet area is cropped to the region's aspect (as
//              "force proportions" in tablet drivers), every screen pixel stays reachable
//   letterbox  aspect-preserving: the whole tablet area maps to the largest centred part of
//              the region with the tablet's aspect
//   display    display tablet (pen on the screen): the whole active area is the whole region;
//              custom areas are ignored and the N-point fit corrects parallax and mounting
#pragma once

#include <glm/glm.hpp>
#include <optional>
#include <string>

namespace cb {

enum class AreaFit { kStretch, kFit, kLetterbox, kDisplay };

const char* areaFitName(AreaFit fit);  // "stretch", "fit", "letterbox", "display"
bool parseAreaFit(const std::string& text, AreaFit* out);

struct RectD {
  double x = 0.0, y = 0.0, w = 0.0, h = 0.0;
};

struct AreaMappingConfig {
  AreaFit fit = AreaFit::kFit;
  std::optional<RectD> tablet_area_mm;    // default: the whole active area
  std::optional<RectD> screen_region_px;  // default: the whole screen
  double rotation_deg = 0.0;              // tablet turned clockwise by this angle
};

struct AreaMapping {
  bool ok = false;
  std::string error;  // e.g. a custom area outside the tablet, an empty region
  glm::dmat3 tablet_to_screen{1.0};
  RectD used_region_px;  // the part of the screen the pen reaches
};

AreaMapping computeAreaMapping(const AreaMappingConfig& config, double tablet_w_mm,
                               double tablet_h_mm, double screen_w_px, double screen_h_px);

}  // namespace cb
