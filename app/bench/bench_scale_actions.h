// What a person does at the painter, timed from the act to the frame that shows it, for
// `cloudbrush bench scale`: the painter itself (PaintLoop over a session holding the bundled
// cumulus, at the session's starting view, no tablet: the mouse drives it as on a kiosk without
// a pen) scripted frame by frame through its display's event queue.
//   - drag the light ball (mode 5, the mouse pressed and moved a little each frame): frames per
//     second while the light follows, and each mouse move → the frame showing it on screen;
//     release → the first frame lit by the released light (the
//     drag's coarse light at the drag's scale), and → the frame after it (the light swept in
//     full, full resolution);
//   - place a picture and a model (PlaceShape, the bench tools' silhouette and torus) → the lit
//     frame that shows the new cloud;
//   - the wind (W) on the 256³ cloud: frames per second while it blows;
//   - Camera mode (1), the view turned by dragging across the cloud: frames per second while it
//     turns (the painting view's own drag, not the no-tablet orbit), and each mouse move → the
//     frame showing it on screen.
// Each act is also timed in a second painter run with the painter's earlier choices, the
// baseline in the same process: the light volume swept in full every drag frame, the whole frame
// re-rendered after a placement, moving frames at the moving scale; the light drag and its
// release at the moving scale.
#pragma once

#include <string>

#include "app/render/gl/display.h"
#include "app/render/volume_renderer.h"
#include "app/volume/sky_extent.h"
#include "app/volume/volume.h"

namespace cb {

struct PainterActionFigures {
  double light_drag_fps = -1;         // median frame while the light is dragged
  double light_release_ms = -1;       // mouse released → glFinish of the lit frame, median
  double light_release_full_ms = -1;  // → glFinish of the frame with the full light, full res
  double place_picture_ms = -1;  // PlaceShape (picture) issued → glFinish of the frame showing it
  double place_model_ms = -1;    // the same for a model
  double wind_fps = -1;          // median frame while the wind blows
  double camera_drag_fps = -1;   // median frame while the view is dragged round in Camera mode
  // A drag's mouse move → the frame drawn from it on screen (the display's present time), median.
  double light_drag_seen_ms = -1, camera_drag_seen_ms = -1;
  // Process CPU (all threads; the figure to compare on a loaded machine), median: a drag
  // frame, the release to its lit frame, a wind frame.
  double light_drag_cpu_ms = -1, light_release_cpu_ms = -1, wind_cpu_ms = -1;
  double camera_drag_cpu_ms = -1;
  // The moving frames (the wind, the view dragged round) drawn each way (moving_frames.h).
  long moving_reprojected = 0, moving_reduced = 0;
  int drag_frames = 0, wind_frames = 0;  // frames the medians are over
};

// One scripted painter run at width×height over `cumulus` in a sky of `sky`; `baseline`: the
// earlier choices (see above). Files it needs are written under `dir`.
PainterActionFigures measurePainterActions(Display& display, VolumeRenderer& renderer,
                                           const Volume& cumulus, int width, int height,
                                           const SkyExtent& sky, const std::string& dir,
                                           bool baseline);

}  // namespace cb
