// Parameters of the stroke-to-cloud mapping (thesis ch. 6), read from config/mapping.toml.
// Every field has the default the thesis (or this product) settled on, so a missing file or key
// falls back to a working mapping.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace cb {

enum class MappingMethod : uint8_t {
  kHybrid = 0,       // HMM: circle growth + sphere mapping + edge mapping (§6.3–6.6)
  kRayMarching = 1,  // RMM: each pixel grows voxels along its view ray (§6.1)
  kSheet = 2,        // a wide, thin, flat layer on the canvas (stratus; sheet_mapping.h)
};

struct CircleGrowthConfig {
  int initial_diameter_px = 128;    // §6.3.3, Table 6.1
  int min_radius_px = 4;            // smallest circle tried (§6.3.3: "between 128 and 4 pixels")
  int directions = 16;              // candidates on each accepted circle's perimeter (§6.3.2)
  float accept_white_ratio = 0.8f;  // R_w threshold (§6.3.3)
  float drop_empty_ratio = 0.5f;    // R_e threshold: drop the direction (§6.3.3)
  // The thesis counts a pixel white at exactly 1.0 and empty at exactly 0.0 (§6.3.3): its
  // footprints are ink masks whose painted body is full ink, and everything "that falls below
  // the circle fill threshold" is left to edge mapping (§6.5–6.6). The real brushes' footprints
  // are graded: bristle striations (2D, §5.3.2; skeleton, §5.2.2) and soft rims (3D) hold
  // almost no pixel near the peak, so a near-peak threshold (0.95) grew no circle for the 2D and
  // skeleton brushes and left the 3D brush's rim (~45 % of its ink) to edge mapping, whose
  // scatter along view rays is the streak §6.6.1 rejects (Fig. 6.17). The body of a graded
  // stroke is where its ink is at least half its peak (the half-maximum width of a soft
  // profile); the fainter rim is the edge.
  float white_threshold = 0.5f;
  float empty_threshold = 0.05f;
  // Judge white against the footprint's own peak: white at >= white_threshold · peak. A brush
  // whose ink never quite saturates (a peak of 0.92) still has a body. Off: absolute.
  bool white_relative_to_peak = true;
  // After growth from the first circle stops, seed again on the stroke path wherever white
  // pixels remain unmasked (disjoint parts of a footprint). Not in the thesis.
  bool reseed_along_path = true;
  // Where the Empty Test is made. The thesis tests the initial (largest) circle, which drops
  // every direction on a stroke thinner than the initial diameter; testing the smallest circle
  // lets circles follow thin strokes too, at the price of more, smaller circles.
  bool empty_test_on_smallest = true;
};

struct SphereMappingConfig {
  float density = 1.0f;            // density at a sphere's core before noise (§6.5: 1.0)
  float edge_softness = 0.2f;      // fraction of the radius over which density fades to 0
  float noise_erosion = 0.2f;      // how far (fraction of radius) noise eats into the surface
  float noise_modulation = 0.35f;  // interior density = density * (1 - m + m * noise)
  // The paint view's ray through a circle's outline crosses this much of its sphere, in voxels
  // (sphereFillRadius): a sphere filled to the circle's own radius is seen edge-on there and its
  // rim is translucent, so a thin stroke's cloud looks thinner than its ink.
  float outline_chord_voxels = 2.5f;
  // Billows (billows.h): each sphere's radius is scaled by 1 + amplitude·u², u a smooth seeded
  // noise in [0, 1] of its circle's centre with features `billow_feature_radii` × the
  // stroke's median circle radius across, so a stroke of even width is a row of larger and smaller
  // lobes, not a tube. 0 (journals recorded before the key) leaves the radii as they were.
  // Built in 0 (as journals before the key); the product's 1.4 is config/mapping.toml's.
  float billow_amplitude = 0.0f;
  float billow_feature_radii = 1.0f;
  // Edge puffs (billows.h edgePuffs): the chance a sphere carries a small sphere on its surface;
  // 0 (journals recorded before the key) none.
  float puff_probability = 0.0f;  // built in 0; config/mapping.toml 0.7
};

struct EdgeMappingConfig {
  int samples_per_pixel = 8;  // Gaussian scatter samples per leftover pixel (§6.6.2)
  float depth_sigma_of_radius = 1.0f / 3.0f;  // σ along the view ray = R_S / 3 (§6.6.2)
  // Floor for that σ, in voxels: a pixel next to a tiny circle still gets enough depth to be
  // seen from the paint view.
  float min_depth_sigma_voxels = 0.75f;
  // σ across the view ray, in footprint pixels at the sample's depth: small, so the silhouette
  // seen from the paint view stays where the footprint put it.
  float lateral_sigma_px = 0.5f;
  float density_scale = 2.0f;  // voxel density = footprint value * scale (clamped to 1)
  // Where P_t, the point where a sphere about P_S touches the pixel's ray, is taken: true, at
  // P_S's view depth (no tail along the paint view's rays); false, the ray's closest point to
  // P_S (§6.6.2 as written; journals recorded before this key replay with false).
  bool tangent_at_sphere_depth = true;
};

struct RayMarchingConfig {
  float density = 1.0f;  // density of the voxels grown along each ray
};

struct SheetConfig {
  float sigma_voxels = 2.0f;  // the layer's half-thickness (Gaussian σ across the plane)
  float erosion = 0.6f;       // how much the noise thins the layer into wisps (0 = solid)
};

struct NoiseTextureConfig {
  uint32_t seed = 20161;        // seeds the pre-generated simplex-noise texture
  int size = 64;                // texels per side; the texture tiles, one texel per voxel
  float period_voxels = 32.0f;  // the base octave's feature size, in voxels
  int octaves = 3;
};

struct MappingConfig {
  MappingMethod method = MappingMethod::kHybrid;
  CircleGrowthConfig circles;
  SphereMappingConfig spheres;
  EdgeMappingConfig edges;
  RayMarchingConfig ray_marching;
  SheetConfig sheet;
  NoiseTextureConfig noise;
};

// Reads a mapping config from a TOML file. Missing keys keep their defaults. Throws
// std::runtime_error naming the file, key and problem for a parse error, a wrong type or an
// out-of-range value.
MappingConfig loadMappingConfig(const std::string& path);
// The same from TOML text in memory (a journal's recorded settings); `name` stands for the file.
// Keys the text lacks keep `absent`'s values (app/session/recorded_settings.h passes the values
// that reproduce the version that wrote the text).
MappingConfig parseMappingConfigText(std::string_view text, const std::string& name,
                                     const MappingConfig& absent = MappingConfig{});
// Every field as mapping.toml text that loadMappingConfig reads back to the same values (floats
// with 9 significant digits): the mapping in force, as a journal records it.
std::string formatMappingConfig(const MappingConfig& config);
// Checks ranges; throws std::invalid_argument naming the field.
void validate(const MappingConfig& config);

const char* toString(MappingMethod method);
// "hybrid"/"hmm" or "ray-marching"/"rmm"; false if unknown.
bool parseMappingMethod(const std::string& text, MappingMethod* method);

}  // namespace cb
