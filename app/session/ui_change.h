// Typed UI changes: everything a person does to the session besides drawing with the pen (thesis
// Appendix A: modes, camera, canvas, light, brush, mapping, erase, undo/redo, delete). The shell
// produces them from keys, the pen and the menu; PaintSession applies them; the journal keeps
// them. This file is the one place that formats and parses them for the journal:
//
//   record  text                                  change
//   Mode    camera|canvas|paint|erase|light       SetMode
//   Ui      camera=EX,EY,EZ,TX,TY,TZ,FOV[,MOVE]    SetCamera (eye, target, vertical fov degrees;
//                                                 MOVE orbit|pan|zoom|view, absent = set)
//   Ui      camera_orbit=DEG                      SetCamera: Camera::reference() orbited (format 1)
//   Ui      brush=2d|3d|skeleton                  SetBrush
//   Ui      brush_size=S                          SetBrushSize (0.25 … 8; specification 1.6)
//   Ui      method=hybrid|ray-marching            SetMapping
//   Ui      canvas=ALTITUDE,THICKNESS             SetCanvas (world units)
//   Ui      light=DX,DY,DZ,R,G,B                  SetLight (direction towards the sun, colour)
//   Ui      erase_tool=vacuum|rub-out             SetEraseTool
//   Ui      vacuum_diameter=D | rubout_diameter=D SetEraseDiameter (world units)
//   Ui      vacuum_cut=X,Y,Z,RADIUS               VacuumCut (world units)
//   Ui      pen_capture=on|off                    PenCapture
//   Ui      menu=open|closed                      ShowMenu (the pen menu shown or hidden; 1.2)
//   Ui      pressure_range=LO,HI                  SetPressureRange (calibration/pressure_range.h)
//   Ui      style=NAME                            SetStyle (a render style's name)
//   Ui      place_picture=PATH | place_model=PATH PlaceShape (the file must be there on replay)
//   Ui      morph2=T,CHECKSUM,TARGET              ApplyMorph (TARGET a .vol path or bundled:SEED;
//                                                 CHECKSUM its volumeChecksum, 16 hex digits)
//   Ui      wind2=SPEED,GUST;DX,DZ,STEPS;...      ApplyWind (one DX,DZ,STEPS per segment)
//   Ui      morph=… | wind=…                      the same, as specification 1.1 wrote them
//   Ui      undo | redo | delete_all              Undo, Redo, DeleteAll
//
// Floats are written with 9 significant digits, so parse(format(x)) == x bit for bit.
#pragma once

#include <string>
#include <string_view>
#include <variant>

#include <glm/glm.hpp>

#include "app/brush/brush_config.h"
#include "app/mapping/mapping_config.h"
#include "app/scene/camera.h"
#include "app/tools/cloud_animation.h"
#include "drivers/core/journal.h"

namespace cb {

// The five modes of thesis §3.4–3.5 / Appendix A (keys 1–5).
enum class Mode { kCamera, kCanvas, kPaint, kErase, kLight };
const char* modeName(Mode mode);  // "camera", "canvas", ...
bool parseMode(std::string_view text, Mode* out);

enum class EraseTool { kVacuum, kRubOut };  // thesis §3.5.1, §3.5.2
const char* eraseToolName(EraseTool tool);  // "vacuum", "rub-out"

// How a camera change was made (for the study's event log; the camera itself is the state):
// kSet by the program (auto-rotation stopped, a reset, the good view), kOrbit, kPan and kZoom
// by a pen drag or keys in Camera mode, kView a preset view (top, front, left, perspective).
enum class CameraMove { kSet, kOrbit, kPan, kZoom, kView };
const char* cameraMoveName(CameraMove move);  // "set", "orbit", "pan", "zoom", "view"

namespace ui {
struct SetMode {
  Mode mode;
};
struct SetCamera {
  Camera camera;
  CameraMove move = CameraMove::kSet;
};
struct SetBrush {
  BrushKind brush;
};
// The brush size (app/brush/brush_config.h stroke.size): the footprint grid is `size` times
// coarser than the screen, so the mark and its cloud are `size` times larger. A journal
// without the record paints at its recorded brush.toml's size (1 when that lacks the key).
struct SetBrushSize {
  float size;
};
struct SetMapping {
  MappingMethod method;
};
struct SetCanvas {
  float altitude, thickness;
};
struct SetLight {
  glm::vec3 direction, colour;
};
struct SetEraseTool {
  EraseTool tool;
};
struct SetEraseDiameter {
  EraseTool tool;
  float diameter;
};
struct VacuumCut {
  glm::vec3 centre;
  float radius;
};
// The render style the painter shows (app/render/render_style.h names: thesis, physical, ink,
// cartoon, sketch); the session keeps the name so a replay renders what the participant saw.
struct SetStyle {
  std::string name;
};
// A cloud made from a picture (PNG silhouette or photo) or a 3D model (OBJ, PLY, glTF), placed
// at the canvas altitude as seen from the current view (app/tools); an edit like a stroke.
struct PlaceShape {
  bool model;  // false: a picture
  std::string path;
};
// While the pen is captured by the on-screen UI (menu open, or pressed on a UI target) its
// samples are journalled and calibrated but draw, erase and map nothing.
struct PenCapture {
  bool captured;
};
// The painter's pen menu shown or hidden (M, the upper side button, a choice made on it). It
// changes no cloud; it is journalled so a replay shows the screen as it was and a resumed
// session opens with the menu as it was (specification 1.2).
struct ShowMenu {
  bool open;
};
// The participant's (or, in the kiosk, the operator's) pressure range from the press
// calibration (calibration/pressure_range.h): which part of the pen's pressure feeds the curve,
// for every sample after it. 0 ≤ lo < hi ≤ 1.
struct SetPressureRange {
  float lo = 0.0f, hi = 1.0f;
};
// The painter's animations committed ("apply"): the morph from the cloud as it was into the
// target at t (app/tools/cloud_morph.h), or a wind run (app/tools/cloud_animation.h). Replay
// recomputes the frame from the cloud before it, so the record holds only what names it.
// Records of journal specification 1.1 (`morph=`, `wind=`) were made by the first versions: a
// morph moving each cell rigidly, wind advecting the density step by step. Both are recomputed
// that way still (morphCellBlocks, blowWindStepByStep), so old journals replay to their volume.
struct ApplyMorph {
  std::string target;  // a saved cloud's path, or bundled:SEED
  uint64_t target_checksum = 0;
  float t = 0.0f;
  bool cell_blocks = false;  // a `morph=` record (specification 1.1)
};
struct ApplyWind {
  WindRun run;
  bool step_by_step = false;  // a `wind=` record (specification 1.1)
};
struct Undo {};
struct Redo {};
struct DeleteAll {};
}  // namespace ui

using UiChange = std::variant<ui::SetMode, ui::SetCamera, ui::SetBrush, ui::SetMapping,
                              ui::SetCanvas, ui::SetLight, ui::SetEraseTool, ui::SetEraseDiameter,
                              ui::VacuumCut, ui::PenCapture, ui::SetStyle, ui::PlaceShape, ui::Undo,
                              ui::Redo, ui::DeleteAll, ui::ApplyMorph, ui::ApplyWind, ui::ShowMenu,
                              ui::SetPressureRange, ui::SetBrushSize>;

struct UiRecordText {
  JournalRecordType type;  // kMode or kUi
  std::string text;
};
UiRecordText formatUiChange(const UiChange& change);
// False with *error naming the key and what was expected.
bool parseUiChange(JournalRecordType type, std::string_view text, UiChange* out,
                   std::string* error);

}  // namespace cb
