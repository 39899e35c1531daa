// One lit frame of a volume, rendered offline (EGL surfaceless) into a float target and read
// back as the display-encoded values the painter would show, for the study's render exports
// (app/study/render_export.h turns them into a linear EXR and a PNG).
#pragma once

#include <string>

#include "app/render/image_io.h"
#include "app/scene/camera.h"
#include "app/scene/light.h"
#include "app/volume/volume.h"

namespace cb {

// Renderer options (and the light, when `light` is null) come from render.toml in the config
// directory when present. False with a message naming the stage or file that failed.
bool renderStudyFrame(const Volume& volume, const Camera& camera, const Light* light, int width,
                      int height, ImageRgbaF* frame, std::string* error);

}  // namespace cb
