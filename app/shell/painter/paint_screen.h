// The painter's screen (thesis ch. 3, Appendix A): the scene seen by the session's camera, in
// one of five modes, driven by the pen first and keys second.
//
//   1 Camera  drag the pen to orbit (lower side button held: zoom; after P: pan); R resets,
//             arrows give the top / front / left / perspective views, Shift+arrows pan, −/+
//             zoom; Space starts or stops the auto-rotation (the status line says it runs)
//   2 Canvas  drag up/down to raise or lower the canvas, PgUp/PgDn by one voxel, −/+ thickness
//   3 Paint   the live footprint; the cloud appears when the pen lifts
//   4 Erase   Rub-out while the tip is down (diameter from pressure), or Vacuum: the sphere
//             under the pointer, where its ray meets the canvas's mid-plane (with a pen pressed:
//             the height from pressure, still on the pointer's ray), Space cuts; V switches,
//             −/+ the diameter
//   5 Light   drag the light ball: the sun's direction from the scene origin; −/+ warmer/cooler
//
// Mode keys act only in their mode; a key pressed elsewhere says where it acts
// (command_table.h, the one table the menu and the help overlay read). Every mode: M or the
// pen's upper side button opens the pen menu; H or ? the keys on screen; B brush, N mapping,
// G good view, T style; Ctrl+Z / Ctrl+Y undo and redo; Delete clears the cloud (Ctrl+Z brings it
// back); Ctrl+S saves under a date-time name; C the circle overlay; S the details (developer
// status line and ray-sample statistics). F morphs the cloud into a saved cloud, W starts /
// stops the wind and D turns it; A applies what plays, X leaves it (animation_preview.h).
// Esc or q with unsaved work asks first (again, or Y, quits). Every action answers on screen
// (toast()), in English and Chinese; until the first stroke a hint says how to paint
// (painter_messages.h).
//
// Every change goes to the PaintSession as a typed UI change (app/session/ui_change.h), so it
// is journalled and replays. Drags show a preview and commit one change when the pen lifts.
// The painter (not a kiosk visitor) with a session starts at the session's paint view, still
// and ready; without a session (no pen backend) the bundled cloud orbits. The scene is re-rendered
// only when what it shows changed (volume generation, camera, light); otherwise the cached image
// and the live overlay are composited.
#pragma once

#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/render/changed_region.h"
#include "app/render/footprint_overlay.h"
#include "app/render/hud_overlay.h"
#include "app/render/render_style.h"
#include "app/render/render_target.h"
#include "app/render/temporal_reprojection.h"
#include "app/render/volume_renderer.h"
#include "app/session/paint_session.h"
#include "app/shell/kiosk/visitor_words.h"
#include "app/shell/painter/paint_loop.h"
#include "app/shell/pen_events.h"
#include "app/shell/screen.h"

namespace cb {

class AnimationPreview;
class MousePen;
class PenSource;
class UiOverlay;
struct UiLabel;

class PaintScreen : public Screen {
 public:
  PaintScreen(Display& display, VolumeRenderer& renderer, const Volume& volume, const Light& light,
              const PaintLoopOptions& options);
  ~PaintScreen() override;
  void attachPen(PenSource* pen, PaintSession* session);
  // Selects the pen's calibration profile again (a new one was just saved, e.g. by the kiosk's
  // operator panel) and hands it to the session, which journals it. False without a connected
  // pen (it is selected when the pen connects).
  bool reselectCalibration();
  // Replay (`cloudbrush replay --frames`): the screen shows `session` while a replay of its
  // journal applies the records; it feeds, applies and journals nothing itself, and its update
  // step changes nothing in the session. replayedSample() is told each pen sample's outcome (the
  // live footprint, the cursor, the lit frame after a lift). Needs the GL context current.
  bool showReplay(PaintSession* session, std::string* error);
  void replayedSample(const SampleOutcome& outcome);
  // The circle overlay (C) on or off (a resumed study session restores it).
  void showCircles(bool on) { show_circles_ = on; }
  bool circlesShown() const { return show_circles_; }

  const char* name() const override { return "paint"; }
  void onPenSamples(const std::vector<PenSample>& samples) override;
  // Esc closes the help or menu first; Esc or q with unsaved work asks (tell) before the loop
  // quits on the second press or Y.
  bool onKey(const DisplayEvent& event, int64_t t_ns) override;
  void onCommand(Command command, int64_t t_ns) override;
  void onResize(int, int) override { refined_ = false; }
  void onPointer(const DisplayEvent& event) override;
  bool allowsQuit() const override { return !options_.visitor_mode; }
  // Something was painted (an undoable change, or a stroke open).
  bool hasPaint() const;
  std::string update(const FrameContext& frame) override;
  bool needsFrame() const override;
  // Puts the painting view as last drawn on the screen (a copy of the cached scene, nothing
  // rendered, no cursor); false when none was drawn yet. The kiosk's "reconnect the pen" screen
  // draws over it: a full-resolution refinement there took seconds under an emulated CPU, and
  // the replugged pen waited for it.
  bool drawLastScene(FrameContext& frame);
  bool draw(FrameContext& frame, std::string* error) override;
  void presented(const FrameContext& frame, double frame_ms) override;

  // Fills the summary's totals after the loop ended.
  void finish(PaintLoopSummary* summary) const;
  // What the status line says to a person: mode, brush, size, input, what runs.
  std::string statusLine() const;
  // The kiosk's words for everything this screen says in visitor mode (visitor_words.h: status,
  // menu, help, answers); without them a visitor sees the painter's own. `glyphs`: every
  // character those words use (KioskTexts::allText), for the font atlas. Call before drawing.
  void setVisitorText(VisitorText text, std::string glyphs) {
    visitor_text_ = std::move(text);
    visitor_glyphs_ = std::move(glyphs);
  }
  // What the answer to a Save says (given the saved file's path), in place of "Saved as NAME";
  // `glyphs`: the characters it may use beyond the painter's own. The log names the whole path.
  void setSaveWords(std::function<std::string(const std::string&)> words, std::string glyphs) {
    save_words_ = std::move(words);
    visitor_glyphs_ += glyphs;
  }
  // The developer's line (mapping, canvas altitude, sky size, pen state), shown with S.
  std::string detailLine() const;
  // The answer to the last action while it shows (a few seconds), else "".
  const std::string& toast() const;
  // The first screen's hint, until the first stroke (empty after).
  std::vector<std::string> hint() const;
  bool helpShown() const { return help_open_; }
  // Painted since the last save (or since the start).
  bool unsavedWork() const;
  const std::string& lastSaved() const { return last_saved_; }
  // Where the light ball is drawn, in screen pixels (tests).
  glm::vec2 lightBallOnScreen() const;
  // The vacuum sphere's centre shown (tests).
  const std::optional<glm::vec3>& vacuumCentre() const { return vacuum_centre_; }
  bool menuOpen() const { return menu_open_; }
  bool edgeOnWarning() const { return edge_on_; }
  // The notice above the status line (edge-on view, kiosk countdown or invitation), or "".
  const std::string& notice() const { return notice_; }
  // Commands tapped on the on-screen UI so far (tests).
  const std::vector<Command>& tappedCommands() const { return tapped_; }
  const UiOverlay* ui() const { return ui_.get(); }
  // Where the pen's last sample was on the screen (calibrated pixels), whether it was in
  // proximity, and whether its tip is down (a host screen's own targets beside the painter).
  struct PenPoint {
    float x = 0.0f, y = 0.0f;
    bool in_proximity = false, down = false;
  };
  PenPoint penPoint() const { return {pen_x_, pen_y_, pen_in_proximity_, pen_events_.down()}; }
  // The view being shown (a drag preview, the auto-rotation, or the session's camera).
  Camera shownCamera() const;
  // The morph or wind shown, if any (tests).
  const AnimationPreview* animation() const { return animation_.get(); }

 private:
  void handleEvent(const PenEvent& event, const MappedSample& mapped);
  // The brush size `steps` steps of [ / ] larger (negative: smaller), journalled, said.
  void stepBrushSize(int steps, int64_t t_ns);
  // One raw sample (tablet or mouse) through the session, the overlay and the pen events.
  void feedSample(const PenSample& sample);
  void repeatRestingPen();
  void apply(const UiChange& change, int64_t t_ns);
  // Shows or hides the pen menu; the session journals it (ui::ShowMenu).
  void setMenu(bool open, int64_t t_ns);
  // The footprint overlay, cursor and lift timing after the session mapped a sample.
  void afterSample(const SampleOutcome& outcome, std::chrono::steady_clock::time_point received);
  void say(const std::string& message);  // stderr only
  // On screen for a few seconds (or for_ns), and stderr.
  void tell(const std::string& message, int64_t for_ns = 0);
  // The command seams (paint_screen_commands.cpp).
  void onChoiceCommand(Command command, int64_t t_ns);
  void onViewCommand(Command command, int64_t t_ns);
  void onSpace(int64_t t_ns);
  void onSizeCommand(Command command, int64_t t_ns);
  void onCloudCommand(Command command, int64_t t_ns);
  void openLastSaved(int64_t t_ns);
  void saveCloud();
  // Where Save writes and Open and the morph look (PaintLoopOptions::save_dir).
  const std::string& saveDir() const;
  void updateVacuumCentre(const MappedSample& mapped);
  // The mouse held still sends no events; a tablet streams samples. While the button is held in
  // a stroke the last position is fed again, so a stroke held still ends as with a pen.
  void repeatHeldMouse();
  bool showsSession() const;
  void warnIfEdgeOn();
  const Volume& shownVolume() const;
  Light shownLight() const;
  // The renderer brought up to date with what is shown; while a morph or the wind plays (the
  // whole cloud changes every frame) changed slots are listed whole, not compared texel by texel.
  SyncStats syncShown();
  bool paintingSetUp(std::string* error);
  void drawStill(FrameContext& frame, PaintFrameInfo* info);
  // What a scene render did this frame (renderScene may run twice: after a late-latched lift).
  struct SceneWork {
    bool refine = false;  // a refinement to full resolution was cast
    double sync_ms = 0.0, render_ms = 0.0;
    long long rendered_pixels = 0;
    float render_scale = 0.0f;
  };
  // Casts what the cached scene lacks (stale: all or the changed region; else a refinement).
  void renderScene(SceneWork* work);
  bool sceneStale() const;
  // A stroke is being drawn (ink_first): a refinement waits for its lift.
  bool inkLive() const;
  bool drawOverlays(std::string* error);
  std::vector<HudItem> hudItems() const;
  // One whole frame: the scene (cached or cast), the ink, the heads-up items, the UI.
  bool drawPass(FrameContext& frame, PaintFrameInfo* info, std::string* error);
  // Late ink (PaintLoopOptions::late_ink): after the frame is made, the samples that came
  // meanwhile are latched and only the pixels they changed are drawn again (or, when they
  // changed more than the ink — a lift, the view — the whole frame is drawn again).
  bool lateInkApplies(const FrameContext& frame, const PaintFrameInfo& info) const;
  bool drawLateInk(FrameContext& frame, PaintFrameInfo* info, std::string* error);
  // The summary's per-frame figures and the print_stats lines of a drawn frame.
  void noteFrame(const PaintFrameInfo& info);
  std::vector<HudItem> hud_items_;  // the heads-up items the last drawOverlays drew
  // After a lift: whether re-rendering `region` at full resolution, at the cost per pixel the
  // last full-resolution frames took, still shows it within options_.lift_budget_ms of the lift.
  bool liftFitsFullResolution(const ScreenRegion& region) const;
  void learnFullResolutionCost(double render_ms, const ScreenRegion& region);
  void drawUi(const FrameContext& frame);
  void appendStatsLabels(int w, int h, std::vector<UiLabel>* labels) const;
  void selectCalibration(uint64_t tool_serial);
  int64_t clockNs() const;  // now on the frame loop's clock
  Camera presetView(Command command) const;
  // Morph and wind (paint_screen_animation.cpp).
  void onAnimationCommand(Command command, int64_t t_ns);
  void advanceAnimation(const FrameContext& frame);
  bool animationPlaying() const;
  std::unique_ptr<AnimationPreview> animation_;
  // A frame while the view moves (orbit, a drag turning the view, morph, wind) into `target`:
  // full resolution by temporal reprojection where it applies and moving_path_ chooses it
  // (paint_screen_reprojection.cpp), else the reduced scale and region in `options`. `sync`:
  // what this frame's sync changed. Returns whether it was reprojected.
  bool renderMoving(long frame, int width, int height, RenderOptions options, const SyncStats& sync,
                    GLuint target);
  // This frame was a moving one of this kind, reprojected or not: measured at its present.
  struct MovingFrameDrawn {
    int kind = 0;  // moving_path_'s index
    bool reprojected = false;
  };
  std::optional<MovingFrameDrawn> moving_frame_drawn_;
  long frame_index_ = 0;            // the frame loop's index of the frame being drawn
  long moving_frames_[2] = {0, 0};  // reduced, reprojected
  std::unique_ptr<TemporalReprojection> reprojection_;
  bool reprojection_failed_ = false;
  std::string reprojection_key_;          // the shading inputs its history was made with
  long reprojection_frame_ = -2;          // the frame loop's index of the last reprojected frame
  uint64_t reprojection_generation_ = 0;  // the volume's generation then

  Display& display_;
  VolumeRenderer& renderer_;
  const Volume& volume_;
  Light light_;
  PaintLoopOptions options_;
  PenSource* pen_ = nullptr;
  PaintSession* session_ = nullptr;
  PenEventDeriver pen_events_;
  std::vector<PenEvent> events_;
  float pen_x_ = 0.0f, pen_y_ = 0.0f;  // the last sample's screen position (penPoint)
  bool pen_in_proximity_ = false;

  // Auto-rotation
  bool orbiting_ = true;
  float orbit_degrees_ = 0.0f;
  // How moving frames are drawn (renderMoving), measured apart for the view turning (orbit, a
  // drag) and for an animation changing the volume (morph, wind: little history is kept).
  MovingPathChooser moving_path_[2];
  float moving_scale_;
  bool refined_ = false;  // the still image is at full resolution

  // Drags (preview until the pen lifts)
  std::optional<Camera> drag_camera_;
  CameraMove drag_move_ = CameraMove::kOrbit;  // what the camera drag does (journalled)
  bool pan_drag_ = false;                      // P: a Camera-mode drag pans instead of orbiting
  std::optional<Canvas> drag_canvas_;
  std::optional<Light> drag_light_;
  // The light drag's own scale (PaintLoopOptions::light_drag_frame_ms), adapted from the time
  // of each drag frame (its update's start to its present); and the release, whose first frame
  // still reads the coarse light, for the released light at the drag's scale (the frame after
  // it sweeps the light in full at full resolution).
  float light_drag_scale_ = 0.5f;
  std::chrono::steady_clock::time_point iteration_start_{};
  bool light_drag_frame_ = false;
  bool light_release_pending_ = false;
  glm::vec2 drag_start_{0.0f};
  uint32_t side_buttons_ = 0;
  std::optional<glm::vec3> vacuum_centre_;

  // Pen and painting
  int last_connection_ = -1;
  bool pen_connected_once_ = false;
  uint64_t tool_serial_ = 0;
  FootprintOverlay overlay_;
  RenderTarget scene_;
  bool overlay_ready_ = false;
  struct SceneKey {
    uint64_t volume = 0, generation = 0;
    Camera camera;
    Light light;
    bool stats = false;
    RenderStyle style = RenderStyle::kThesis;
    bool operator==(const SceneKey& o) const;
  };
  std::optional<SceneKey> drawn_;  // what the cached scene shows
  SceneKey currentKey() const;
  RenderStyle currentStyle() const;
  bool lit_pending_ = false;
  bool refine_pending_ = false;
  ScreenRegion unrefined_;  // the part of scene_ still at the reduced resolution
  std::chrono::steady_clock::time_point lift_time_;
  int64_t lift_sample_ns_ = 0;  // the lift sample's timestamp (the pen's clock)
  double lift_mapping_ms_ = 0.0;
  // Full-resolution ray-cast milliseconds per pixel of the re-rendered region, from the last
  // timed full-resolution frames (0: none yet); liftFitsFullResolution predicts with it.
  double full_ms_per_pixel_ = 0.0;
  size_t texels_this_frame_ = 0;
  OverlayCursor cursor_;
  HudOverlay hud_;
  bool show_stats_ = false, show_circles_ = false;
  bool menu_open_ = false;
  bool replay_view_ = false;  // showReplay(): drawn from a replay, no input of its own
  std::unique_ptr<UiOverlay> ui_;
  bool ui_failed_ = false;
  bool pointer_over_ui_ = false;
  bool mouse_down_ = false;
  std::unique_ptr<MousePen> mouse_;  // the mouse as the pen, once it was used without a tablet
  // A connected pen without pressure (tip only) paints at this level (−/+ in Paint mode).
  float tip_only_pressure_ = 0.6f;
  bool tipOnlyPen() const;
  bool pointer_moved_ = false;  // a mouse event since the last frame  // the pen or mouse was over
                                // a UI target last frame
  std::string notice_;          // shown above the status line
  VisitorText visitor_text_;    // the kiosk's words (visitor mode), or none
  std::string visitor_glyphs_;  // their characters (and the save words')
  std::function<std::string(const std::string&)> save_words_;
  bool visitorWords() const { return options_.visitor_mode && bool(visitor_text_); }
  std::vector<Command> tapped_;
  bool visitorAllows(Command command) const;
  bool edge_on_ = false;  // the session's view is nearly edge-on to the canvas
  std::string last_message_;
  static constexpr int64_t kToastNs = 4'000'000'000;
  std::string toast_;
  int64_t toast_until_ns_ = 0;
  bool help_open_ = false;
  int64_t quit_armed_until_ns_ = 0;
  bool quit_confirmed_ = false;
  uint64_t saved_volume_ = 0, saved_generation_ = 0;
  std::string last_saved_;
  int64_t last_mouse_sample_ns_ = 0;
  PenSample last_pen_sample_{};  // the tablet's newest, repeated while it rests (repeatRestingPen)

  // Summary figures
  long pen_samples_ = 0, strokes_seen_ = 0;
  std::vector<double> moving_frame_ms_, painting_frame_ms_;
  std::vector<double> pen_up_to_lit_ms_, mapping_ms_, sync_ms_, render_ms_, refined_ms_;
  std::vector<double> lift_sample_to_lit_ms_, lift_sample_to_refined_ms_;
  long refined_frames_ = 0;
  PaintFrameInfo last_info_;
};

}  // namespace cb
