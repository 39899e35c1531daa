// Brush parameters (config/brush.toml). Every field has a sane default, so a missing or broken
// file still gives a working brush; loadBrushConfig reports what was wrong and where.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "app/brush/stroke_result.h"

namespace cb {

// The brush size's range (stroke.size, the journal's `brush_size=`) and the factor one step of
// [ / ], the menu's − / + or a wheel click changes it by.
constexpr float kMinBrushSize = 0.25f, kMaxBrushSize = 8.0f;
constexpr float kBrushSizeStep = 1.25f;
// The size one step up (steps > 0) or down from `size`, clamped to the range.
float steppedBrushSize(float size, int steps);

struct StrokeParams {
  float spacing_px = 1.5f;       // arc-length step between dabs of the texture brushes
  float footprint_scale = 1.0f;  // footprint pixels per screen pixel of the paint view
  // The brush size at the start of a session (the painter's [ and ], the pen menu's − / +, the
  // mouse wheel change it, journalled as `brush_size=`): every brush paints its footprint on a
  // grid `size` times coarser than the screen, so the whole mark, and the cloud mapped from it,
  // is `size` times larger; pressure still scales the mark within the size. 1 (the built-in
  // value: footprint pixels are screen pixels) is the size before the key existed; the
  // product's default is config/brush.toml's, chosen there from the thesis's figures.
  float size = 1.0f;
  // The brush's edge swells and narrows along the stroke (billow_profile.h): each dab of the
  // texture brushes is scaled by up to 1 + billow in a lobe and 1 − billow/3 in a neck, a
  // smooth noise of the arc length with lattice points billow_length × the brush's largest
  // diameter apart. 0 (the built-in value): a
  // stroke of even pressure is one width, as before the key existed.
  float billow = 0.0f;
  float billow_length = 1.5f;
  // An open stroke ends by itself when held still / touched only lightly this long (0 = never);
  // the painter copies these into its session (app/session, journalled there).
  int auto_end_still_ms = 2000;
  int auto_end_light_ms = 800;
  // What "touched only lightly" is: true, held down by the calibration's contact hysteresis
  // alone (MappedSample::light_contact); false, the calibrated pressure under 5% (journals
  // recorded before this key, app/session/recorded_settings.h).
  bool auto_end_light_by_hysteresis = true;
};

// Speed -> ink dispersion (thesis §5.1.2, mechanism 3): at or below slow_speed the ink is laid
// solid; at fast_speed and above it is dispersed by max_dispersion (0 = none, 1 = all gone).
struct DispersionParams {
  float slow_speed_px_s = 400.0f;
  float fast_speed_px_s = 4000.0f;
  float max_dispersion = 0.6f;
  float speed_smoothing_ms = 30.0f;  // time constant of the speed estimate
  float noise_scale_px = 6.0f;       // feature size of the dispersion pattern
};

struct Brush2DParams {
  float min_diameter_px = 4.0f;   // at pressure 0
  float max_diameter_px = 40.0f;  // at pressure 1
  int texture_size = 64;
  int bristles = 110;
  unsigned texture_seed = 11;
};

struct Brush3DParams {
  float diameter_px = 56.0f;  // footprint size of the whole 2D sample
  int ink_volume_size = 64;   // thesis §5.3.1: a 64³ ink dataset
  unsigned ink_seed = 7;
  int sample_size = 64;                   // resolution of the ray-marched 2D sample
  float slab_thickness = 0.2f;            // in ink-volume units ([-1,1]), ≈ 1/10 of the volume
  float absorption = 16.0f;               // ink extinction per unit length inside the slab
  float max_tilt_deg = 60.0f;             // tilt is clamped to this before tipping the plane
  float pressure_quantum = 1.0f / 64.0f;  // samples are computed at quantised pressure/tilt,
  float tilt_quantum_deg = 2.0f;          // so cached and fresh samples are identical
  int cache_entries = 1024;
};

struct SkeletonParams {
  float segment_length_px = 9.0f;    // 3 segments between 4 joints (thesis Fig. 5.4)
  float time_step_ms = 1.0f;         // fixed internal Verlet step
  int constraint_iterations = 10;    // thesis §5.2.1
  float gravity_px_s2 = 4000000.0f;  // the predefined acceleration V_acc
  float damping = 0.08f;
  float press_depth = 0.85f;       // pressure 1 lowers the rod by this fraction of the spine
  float paper_softness_px = 2.0f;  // bristles may sink this far below the paper
  int bristles = 40;
  float bristle_spread_px = 10.0f;  // radius of the bristle bundle at the ferrule
  float bristle_splay = 1.5f;       // extra spread of the tip at full pressure
  float bristle_radius_px = 0.9f;
  int bristle_points = 12;         // Bezier evaluation points per bristle
  int max_steps_per_sample = 250;  // caps work after a long pause
  // Bristles are stamped at spine positions this far apart (interpolated between simulation
  // steps), so a fast stroke is continuous; 0 stamps once per step, as journals before the key
  // (app/session/recorded_settings.h).
  float stamp_spacing_px = 1.5f;
  // Simulation steps at the pen's last point after it lifts, stamping, so the trailing
  // bristles reach the stroke's end; 0 (journals before the key) stops at the lift.
  int end_settle_steps = 60;
  unsigned seed = 5;
};

struct BrushConfig {
  BrushKind default_brush = BrushKind::k3D;
  StrokeParams stroke;
  DispersionParams dispersion;
  Brush2DParams brush2d;
  Brush3DParams brush3d;
  SkeletonParams skeleton;
};

// Reads `path` over the defaults in *config. Returns false and appends messages of the form
// "FILE:LINE:COL: what" to *errors when the file is unreadable, malformed or holds out-of-range
// values; fields that were bad keep their defaults.
bool loadBrushConfig(const std::string& path, BrushConfig* config,
                     std::vector<std::string>* errors);
// The same from TOML text in memory (a journal's recorded settings); `name` stands for the file.
bool parseBrushConfigText(std::string_view text, const std::string& name, BrushConfig* config,
                          std::vector<std::string>* errors);
// Every field as brush.toml text that the parsers read back to the same values (floats with 9
// significant digits): the brush in force, as a journal records it.
std::string formatBrushConfig(const BrushConfig& config);
// The shipped config/brush.toml (config_paths.h), or defaults with a message on stderr.
BrushConfig loadDefaultBrushConfig();

const char* brushKindName(BrushKind kind);
bool parseBrushKind(const std::string& name, BrushKind* kind);

}  // namespace cb
