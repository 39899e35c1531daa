// The main job without a display: render the scene once from the fixed reference camera and
// write it as a PNG (8-bit, for people) and an OpenEXR (linear float, for tools).
#pragma once

#include <string>
#include <vector>

#include "app/render/gl/display.h"
#include "app/render/volume_renderer.h"
#include "app/scene/light.h"
#include "app/volume/volume.h"

namespace cb {

struct HeadlessRenderResult {
  std::vector<std::string> written;  // the files, PNG first
  RenderStats stats;
};

// Renders `volume` lit by `light` at the display's size into `out_dir` (created if missing) as
// `<stem>.png` and `<stem>.exr`. False with a message naming the file or stage that failed.
bool renderHeadless(Display& display, VolumeRenderer& renderer, const Volume& volume,
                    const Light& light, const RenderOptions& base, const std::string& out_dir,
                    const std::string& stem, bool collect_stats, HeadlessRenderResult* result,
                    std::string* error);

}  // namespace cb
