// The sky behind the clouds (app/render/sky_settings.h), as a function of the ray direction and
// the pixel; the same formula as app/render/sky_function.cpp (tested against it). Compiled in
// variants: CB_SKY_KIND 1 colour gradient, 2 gradient + LIC cloud layer (seed 002 §3.2.3),
// 3 image; CB_SKY_POSTERISE 1 for the cartoon style. y is up.
uniform vec3 u_sky_zenith;
uniform vec3 u_sky_horizon;
uniform float u_sky_glow;
uniform vec3 u_sky_sun_dir;     // towards the sun, unit
uniform vec3 u_sky_sun_colour;
uniform sampler2D u_sky_layer;  // LIC cloud layer opacity (R8, repeating)
uniform float u_sky_lic_scale;
uniform sampler2D u_sky_image;  // RGBA8, row 0 = the image's top row
uniform vec2 u_sky_image_size;  // texels
uniform vec2 u_sky_frame_size;  // pixels of the frame the image covers

// The cartoon's sky is posterised in its parameters (not per channel, which would shift hues):
// the gradient in 5 bands, the sun's glow and the cloud layer in 3 levels.
float posterise(float v, float levels) {
#if CB_SKY_POSTERISE
  return floor(v * levels + 0.5) / levels;
#else
  return v;
#endif
}

vec3 skyGradient(vec3 dir) {
  float t = posterise(pow(1.0 - max(dir.y, 0.0), 3.0), 5.0);
  float glow = posterise(pow(max(dot(dir, u_sky_sun_dir), 0.0), 24.0), 3.0);
  return mix(u_sky_zenith, u_sky_horizon, t) + u_sky_glow * glow * u_sky_sun_colour;
}

vec3 skyColour(vec3 dir, vec2 pixel) {
#if CB_SKY_KIND == 3
  // Cover the frame, centred, aspect kept; image rows run top-down.
  float scale = max(u_sky_frame_size.x / u_sky_image_size.x, u_sky_frame_size.y / u_sky_image_size.y);
  vec2 from_centre = pixel - 0.5 * u_sky_frame_size;
  vec2 texel = 0.5 * u_sky_image_size + vec2(from_centre.x, -from_centre.y) / scale;
  vec3 c = textureLod(u_sky_image, texel / u_sky_image_size, 0.0).rgb;
#else
  vec3 c = skyGradient(dir);
#if CB_SKY_KIND == 2
  // The far cloud layer on the plane y = 1, fading into the haze towards the horizon.
  vec2 uv = dir.xz / max(dir.y, 1e-3) * u_sky_lic_scale;
  float o = posterise(texture(u_sky_layer, uv).r * smoothstep(0.03, 0.3, dir.y), 3.0);
  c = mix(c, 0.92 * u_sky_sun_colour + 0.08 * u_sky_horizon, 0.85 * o);
#endif
#endif
#if CB_SKY_POSTERISE && CB_SKY_KIND == 3
  // A picture: its luminance in 5 bands, hues kept (per channel would shift them).
  float luma = dot(c, vec3(0.2126, 0.7152, 0.0722));
  c *= (floor(luma * 5.0 + 0.5) / 5.0) / max(luma, 1e-3);
#endif
  return clamp(c, 0.0, 1.0);
}
