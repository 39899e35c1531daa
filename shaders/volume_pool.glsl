// The volume as a brick pool (app/render/brick_pool.h), linked first into the ray caster: every
// read of density and light goes through here.
//
// u_pool holds 17³-texel slots, RG8 (r = density, g = transmittance towards the light); the slot
// of brick b holds voxels 16b … 16b+16 on each axis (clamped to the volume). u_bricks gives each
// 16³ brick its slot in slot units (.w = 0: the empty slot (0,0,0), all density 0).
//
// A voxel-space point p (voxel i covers [i, i+1)) is read in the slot of brick
// b = ⌊(p − ½)/16⌋, whose "cell" is [16b + ½, 16b + 16½): trilinear filtering there reads voxels
// ⌊p − ½⌋ and ⌊p − ½⌋ + 1, both in the slot, so the value is the dense texture's.
//
// Positions are carried in fixed point, 1/256 of a voxel: the texture unit's trilinear weights
// have 8 fractional bits (llvmpipe rounds coordinate·size·256 to the nearest integer, as most
// GPUs do), so a position rounded the same way and moved by a whole number of texels (the slot's
// offset, exact in float) filters with exactly the weights the dense texture used. With
// power-of-two grid and pool sizes every scaling is exact too, and the pool reproduces the dense
// texture bit for bit. Positions are clamped to the cell (in pool texels [17s + ½, 17s + 16½]):
// at the volume's faces that is the dense texture's CLAMP_TO_EDGE; inside it never moves a
// position the march puts in the cell.
uniform sampler3D u_pool;
uniform usampler3D u_bricks;
uniform vec3 u_dims;             // voxels
uniform ivec3 u_brick_max;       // bricks per axis − 1
uniform vec3 u_inv_pool_fixed;   // 1 / (pool size in texels · 256)

const float kBrickVoxels = 16.0;
const float kSlotTexels = 17.0;
const float kFixed = 256.0;  // fixed-point steps per voxel

// The slot of one cell.
struct PoolBrick {
  vec3 cell_lo;   // voxel-space corner of the cell, 16b + ½
  vec3 to_pool;   // fixed-point pool position = fixed-point voxel position + to_pool
  vec3 lo, hi;    // the cell's clamp range, fixed-point pool positions
  bool empty;     // the empty slot: density 0 everywhere in the cell
};

// Dense texture coordinate -> voxel position in fixed point (whole numbers of 1/256 voxel).
vec3 fixedVoxel(vec3 coord) {
  return roundEven(coord * (u_dims * kFixed));
}

// The cell holding fixed-point voxel position `q`.
PoolBrick poolBrickAt(vec3 q) {
  ivec3 b = clamp(ivec3(floor((q * (1.0 / kFixed) - 0.5) * (1.0 / kBrickVoxels))), ivec3(0),
                  u_brick_max);
  uvec4 slot = texelFetch(u_bricks, b, 0);
  PoolBrick pb;
  vec3 brick_lo = vec3(b) * kBrickVoxels;
  vec3 slot_lo = vec3(slot.xyz) * kSlotTexels;
  pb.cell_lo = brick_lo + 0.5;
  pb.to_pool = (slot_lo - brick_lo) * kFixed;
  pb.lo = (slot_lo + 0.5) * kFixed;
  pb.hi = (slot_lo + (kSlotTexels - 0.5)) * kFixed;
  pb.empty = slot.w == 0u;
  return pb;
}

// Density and transmittance at fixed-point voxel position q in pb's cell.
vec2 samplePool(vec3 q, PoolBrick pb) {
  return textureLod(u_pool, clamp(q + pb.to_pool, pb.lo, pb.hi) * u_inv_pool_fixed, 0.0).rg;
}

// Density and transmittance at dense texture coordinate `coord` (voxel i at (i + ½)/dims; what
// textureLod of the dense texture gave, CLAMP_TO_EDGE outside): one indirection fetch and one
// trilinear fetch. The ray march reads through samplePool, keeping a cell's PoolBrick for the
// samples in it.
vec2 sampleVolume(vec3 coord) {
  vec3 q = fixedVoxel(coord);
  return samplePool(q, poolBrickAt(q));
}
