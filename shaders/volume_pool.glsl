// The volume as a brick pool (app/render/brick_pool.h), linked first into the ray caster: every
// read of density and light goes through here.
//
// u_pool holds 20³-texel slots as a 2D array texture (20 × 20 texels on 20 layers) of RGBA8: r, g =
// density and transmittance towards the light of the texel's voxel, b, a = those of the voxel
// above it in z (the next layer's r, g). The slot of brick b holds voxels 16b … 16b+19 on each
// axis (its 16, the first of the next brick and an apron of 3 more; indices clamped to the
// volume). u_bricks gives each 16³ brick its slot in slot units, as RGBA8 read with nearest
// filtering (a = 0: the empty slot (0,0,0), all density 0).
//
// A voxel-space point p (voxel i covers [i, i+1)) is read in the slot of brick
// b = ⌊(p − ½)/16⌋, whose "cell" is [16b + ½, 16b + 16½): trilinear filtering there reads voxels
// ⌊p − ½⌋ and ⌊p − ½⌋ + 1, both in the slot, so the value is the dense texture's. The ray march
// looks a slot up once per chunk of up to 4 samples, in the cell of the chunk's lowest corner:
// the apron holds the rest of the chunk (3 steps of at most one voxel).
//
// Trilinear filtering is one bilinear fetch (4 texels; a 3D texture's trilinear fetch gathers 8,
// and llvmpipe pays per gathered texel) of layer ⌊p.z − ½⌋ and a lerp in z here.
//
// Positions are carried in fixed point, 1/256 of a voxel: the texture unit's filter weights have
// 8 fractional bits (llvmpipe rounds coordinate·size·256 to the nearest integer, as most GPUs
// do). A fixed-point pool position p (a whole number < 2^21) passed as p / (size·256) comes back
// as p exactly whatever the size (relative error ≤ 3·2^-24, under ½ after rounding), so a
// position rounded the same way and moved by a whole number of texels (the slot's offset, exact
// in float) filters in x and y with exactly the weights the dense texture used. In z the shader
// computes the same 8-bit weight and the lerp as llvmpipe's texture unit does it on 8-bit values
// (v0 + ⌊(w·(v1 − v0) + 128) / 256⌋, its rounding multiply), after the same bilinear steps in x and
// y, so the pool reproduces the dense texture's images bit for bit on llvmpipe
// (tests/golden/render/dense_reference_test); a texture unit that rounds otherwise differs by at
// most one step of 8 bits per sample.
//
// u_pool_smooth, the pool's companion (same size and slots, RG16), holds each texel's density
// smoothed over about 3 voxels (the mean of the 8 voxels ±1 on each axis) and the next layer's:
// read in the same slot (sampleSmoothDensity: the bilinear fetch, then a lerp in z, here in
// float: 16 bits need no 8-bit steps) it gives the mean of 8 trilinear reads ±1 voxel apart in
// one fetch.
uniform sampler2DArray u_pool;
uniform sampler2DArray u_pool_smooth;
uniform sampler3D u_bricks;
uniform vec3 u_dims;              // voxels
uniform ivec3 u_brick_max;        // bricks per axis − 1
uniform vec3 u_inv_brick_dims;    // 1 / bricks per axis
uniform vec3 u_inv_pool_fixed;    // 1 / (pool size in texels · 256); z unused (layers by index)

const float kBrickVoxels = 16.0;
const float kSlotTexels = 20.0;
const float kFixed = 256.0;  // fixed-point steps per voxel

// The slot of one cell.
struct PoolBrick {
  vec3 to_pool;  // fixed-point pool position = fixed-point voxel position + to_pool
  vec3 lo, hi;   // the slot's readable range, fixed-point pool positions
  bool empty;    // the empty slot: density 0 everywhere in the cell
};

// Dense texture coordinate -> voxel position in fixed point (whole numbers of 1/256 voxel).
vec3 fixedVoxel(vec3 coord) {
  return roundEven(coord * (u_dims * kFixed));
}

// The slot of the cell holding fixed-point voxel position `q` (cells at the volume's faces extend
// outwards).
PoolBrick poolBrickAt(vec3 q) {
  ivec3 b = clamp(ivec3(floor((q * (1.0 / kFixed) - 0.5) * (1.0 / kBrickVoxels))), ivec3(0),
                  u_brick_max);
  vec4 slot_n = textureLod(u_bricks, (vec3(b) + 0.5) * u_inv_brick_dims, 0.0);
  vec3 slot_lo = floor(slot_n.xyz * 255.0 + 0.5) * kSlotTexels;
  PoolBrick pb;
  pb.to_pool = (slot_lo - vec3(b) * kBrickVoxels) * kFixed;
  pb.lo = (slot_lo + 0.5) * kFixed;
  pb.hi = (slot_lo + (kSlotTexels - 0.5)) * kFixed;
  pb.empty = slot_n.a == 0.0;
  return pb;
}

// Density and transmittance at fixed-point pool position p (inside a slot): the texture unit's
// bilinear fetch in x and y of layer ⌊p.z − ½⌋, whose texels hold that layer's bytes (rg) and the
// next layer's (ba), then the lerp in z as the texture unit does it in 8 bits. The fetch returns
// byte·(1/255) rounded to float (llvmpipe's unorm8 conversion): round(c·255) is the byte again,
// and (c.ba − c.rg)·255·w lies within 0.03 of the whole number w·(v1 − v0), so the + ½ keeps the
// floor off whole numbers and the rise is exact; (byte)·(1/255) is the float the texture unit
// would have returned for that byte.
vec2 poolFetch(vec3 p) {
  float z = p.z - 0.5 * kFixed;
  float layer = floor(z * (1.0 / kFixed));
  float w = z - layer * kFixed;
  vec4 c = textureLod(u_pool, vec3(p.xy * u_inv_pool_fixed.xy, layer), 0.0);
  vec2 lower = round(c.rg * 255.0);
  vec2 rise = floor(((c.ba - c.rg) * (255.0 * w) + 128.5) * (1.0 / kFixed));
  return (lower + rise) * (1.0 / 255.0);
}

// The smoothed density at fixed-point pool position p: u_pool_smooth's r (this layer) and g
// (the next) fetched bilinearly in layer ⌊p.z − ½⌋, as poolFetch, and lerped in z.
float poolFetchSmooth(vec3 p) {
  float z = p.z - 0.5 * kFixed;
  float layer = floor(z * (1.0 / kFixed));
  vec2 c = textureLod(u_pool_smooth, vec3(p.xy * u_inv_pool_fixed.xy, layer), 0.0).rg;
  return mix(c.r, c.g, (z - layer * kFixed) * (1.0 / kFixed));
}

// Density and transmittance at fixed-point voxel position q, anywhere in pb's slot (clamped to
// it: beyond the volume's faces that is the dense texture's CLAMP_TO_EDGE).
vec2 samplePool(vec3 q, PoolBrick pb) {
  return poolFetch(clamp(q + pb.to_pool, pb.lo, pb.hi));
}

// The same for a sample of a chunk whose lowest corner lies in pb's cell: inside the slot by
// construction, except below the volume's low faces (clamped there, as CLAMP_TO_EDGE does).
vec2 sampleChunk(vec3 q, PoolBrick pb) {
  return poolFetch(max(q + pb.to_pool, pb.lo));
}

// Density and transmittance at dense texture coordinate `coord` (voxel i at (i + ½)/dims; what
// textureLod of a dense texture gave): one slot lookup and one trilinear fetch. For sample sites
// off the march (an iso-surface's normal, light and inner surface).
vec2 sampleVolume(vec3 coord) {
  vec3 q = fixedVoxel(coord);
  return samplePool(q, poolBrickAt(q));
}

// The smoothed density (u_pool_smooth) at dense texture coordinate `coord`.
float sampleSmoothDensity(vec3 coord) {
  vec3 q = fixedVoxel(coord);
  PoolBrick pb = poolBrickAt(q);
  return poolFetchSmooth(clamp(q + pb.to_pool, pb.lo, pb.hi));
}

#if CB_LIGHT_PREVIEW
// While the light ball is dragged, or a morph or the wind plays, the light is read from a coarse
// grid of its own (app/render/reduced_light_sweep.h, light_preview_texture.h) instead of the
// pool's g and a:
// one trilinear fetch of an R8 3D texture over the cloud's box, clamped at its edge.
uniform sampler3D u_light_preview;
uniform vec3 u_preview_scale;   // dense texture coordinate -> the grid's texture coordinate
uniform vec3 u_preview_offset;

float previewTransmittance(vec3 coord) {
  return textureLod(u_light_preview, coord * u_preview_scale + u_preview_offset, 0.0).r;
}
#endif
