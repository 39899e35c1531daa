// The brick pool (app/render/brick_pool.h): slot layout, which bricks get slots, what an edit or
// a light change re-uploads, slot reuse and growth, and that every incremental state renders
// exactly what a fresh upload of the same volume renders.
#include "app/render/brick_pool.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <set>
#include <tuple>

#include <gtest/gtest.h>

#include "app/render/volume_renderer.h"
#include "app/volume/scene_generators.h"
#include "tests/unit/render/gl_test_context.h"

namespace cb {
namespace {

constexpr int kW = 240, kH = 160;

// A soft ball of density around voxel `c` (radius r voxels), marked dirty.
void paintBall(Volume& v, glm::ivec3 c, int r, float density = 1.0f) {
  const VoxelBox box = VoxelBox{c - r, c + r + 1}.intersect(v.bounds());
  for (int z = box.lo.z; z < box.hi.z; ++z)
    for (int y = box.lo.y; y < box.hi.y; ++y)
      for (int x = box.lo.x; x < box.hi.x; ++x) {
        const float d = glm::length(glm::vec3(x, y, z) - glm::vec3(c)) / float(r);
        if (d < 1.0f) v.maxMerge(x, y, z, density * std::min(1.0f, 2.0f * (1.0f - d)));
      }
  v.markDirty(box);
}

// Zeroes a box and gives back the bricks it empties (as the eraser does).
void eraseBox(Volume& v, const VoxelBox& box) {
  for (int z = box.lo.z; z < box.hi.z; ++z)
    for (int y = box.lo.y; y < box.hi.y; ++y)
      for (int x = box.lo.x; x < box.hi.x; ++x)
        if (v.at(x, y, z) != 0.0f) v.voxelForWrite(x, y, z) = 0.0f;
  v.markDirty(box);
  const glm::ivec3 lo = box.lo >> Volume::kBrickShift, hi = (box.hi - 1) >> Volume::kBrickShift;
  for (int bz = lo.z; bz <= hi.z; ++bz)
    for (int by = lo.y; by <= hi.y; ++by)
      for (int bx = lo.x; bx <= hi.x; ++bx) v.releaseEmptyBrick({bx, by, bz});
}

using BrickSet = std::set<std::tuple<int, int, int>>;

BrickSet bricksWithSlots(const BrickPool& pool) {
  BrickSet s;
  const glm::ivec3 d = pool.brickDims();
  for (int z = 0; z < d.z; ++z)
    for (int y = 0; y < d.y; ++y)
      for (int x = 0; x < d.x; ++x)
        if (pool.slotOf({x, y, z}).w) s.insert({x, y, z});
  return s;
}

ImageRgba8 render(VolumeRenderer& r, const Camera& camera, RenderOptions options = {}) {
  RenderTarget target;
  std::string err;
  EXPECT_TRUE(target.create(kW, kH, RenderTarget::Format::kRgba8, &err)) << err;
  r.render(camera, kW, kH, target.fbo(), options);
  return target.readRgba8();
}

TEST(BrickPoolSlot, HoldsTheBrickAndItsHighApronClampedToTheVolume) {
  // A grid that is no multiple of 16, so the last bricks are partial.
  Volume v = makeSparsePuffs(glm::ivec3(40, 24, 33), 3);
  paintBall(v, {38, 22, 31}, 5);  // density up to the far corner
  LightVolume light;
  sweepLightVolume(light, v, Light{}, v.bounds());
  std::vector<uint8_t> slot(BrickPool::kSlotBytes);
  constexpr int S = BrickPool::kSlotTexels;
  for (glm::ivec3 b : {glm::ivec3(0, 0, 0), glm::ivec3(1, 0, 1), glm::ivec3(2, 1, 2)}) {
    packBrickSlot(v, light, b, slot.data());
    int non_zero = 0;
    for (int k = 0; k < S; ++k)
      for (int j = 0; j < S; ++j)
        for (int i = 0; i < S; ++i) {
          const glm::ivec3 voxel = glm::min(b * 16 + glm::ivec3(i, j, k), v.dims() - 1);
          // The texel's own voxel, then the one above it in z (the slot's last layer repeats
          // its own).
          const glm::ivec3 up =
              glm::min(b * 16 + glm::ivec3(i, j, std::min(k + 1, S - 1)), v.dims() - 1);
          const uint8_t* t = &slot[BrickPool::kTexelBytes * size_t((k * S + j) * S + i)];
          ASSERT_EQ(t[0], unorm8(v.at(voxel.x, voxel.y, voxel.z))) << i << "," << j << "," << k;
          ASSERT_EQ(t[1], unorm8(light.at(voxel.x, voxel.y, voxel.z))) << i << "," << j << "," << k;
          ASSERT_EQ(t[2], unorm8(v.at(up.x, up.y, up.z))) << i << "," << j << "," << k;
          ASSERT_EQ(t[3], unorm8(light.at(up.x, up.y, up.z))) << i << "," << j << "," << k;
          non_zero += t[0] != 0;
        }
    EXPECT_GT(non_zero, 0) << "brick " << b.x << "," << b.y << "," << b.z << " holds no density";
  }
}

TEST(BrickPoolSlot, HoldsTheSmoothedDensityOfItsVoxels) {
  // Partial bricks and density up to the far corner, as above.
  Volume v = makeSparsePuffs(glm::ivec3(40, 24, 33), 3);
  paintBall(v, {38, 22, 31}, 5);
  v.set(16, 16, 16, 1.0f);  // a single voxel on a brick corner: its diagonal neighbours read 1/8
  std::vector<uint16_t> slot(BrickPool::kSmoothSlotBytes / 2);
  constexpr int S = BrickPool::kSlotTexels;
  auto byte = [&](glm::ivec3 p) { return int(unorm8(v.at(p.x, p.y, p.z))); };
  for (glm::ivec3 b :
       {glm::ivec3(0, 0, 0), glm::ivec3(1, 0, 1), glm::ivec3(0, 1, 0), glm::ivec3(2, 1, 2)}) {
    packSmoothSlot(v, b, slot.data());
    int non_zero = 0;
    for (int k = 0; k < S; ++k)
      for (int j = 0; j < S; ++j)
        for (int i = 0; i < S; ++i) {
          // The mean of the 8 diagonal neighbours (clamped to the volume) of the texel's voxel,
          // then of the voxel above it (the slot's last layer repeats its own), in 16 bits.
          auto mean = [&](glm::ivec3 t) {
            const glm::ivec3 voxel = b * 16 + t;
            int sum = 0;
            for (int n = 0; n < 8; ++n) {
              const glm::ivec3 o((n & 1) ? 1 : -1, (n & 2) ? 1 : -1, (n & 4) ? 1 : -1);
              sum += byte(glm::clamp(voxel + o, glm::ivec3(0), v.dims() - 1));
            }
            return int(smoothUnorm16(sum));
          };
          const glm::ivec3 t(i, j, k);
          const uint16_t* o = &slot[2 * size_t((k * S + j) * S + i)];
          ASSERT_EQ(int(o[0]), mean(glm::min(b * 16 + t, v.dims() - 1) - b * 16))
              << i << "," << j << "," << k;
          ASSERT_EQ(int(o[1]),
                    mean(glm::min(b * 16 + glm::ivec3(i, j, std::min(k + 1, S - 1)), v.dims() - 1) -
                         b * 16))
              << i << "," << j << "," << k;
          non_zero += o[0] != 0;
        }
    EXPECT_GT(non_zero, 0) << "brick " << b.x << "," << b.y << "," << b.z;
  }
  // The single voxel at (16,16,16): the slot of brick (0,0,0) holds it at texel 16 and its
  // diagonal neighbours (15,15,15) and (17,17,15) as 1/8; (16,16,16) itself reads only its
  // neighbours.
  packSmoothSlot(v, glm::ivec3(0), slot.data());
  auto at = [&](int i, int j, int k) { return int(slot[2 * size_t((k * S + j) * S + i)]); };
  ASSERT_EQ(v.at(15, 15, 15) + v.at(17, 17, 17) + v.at(15, 17, 15), 0.0f) << "puffs nearby";
  EXPECT_EQ(at(15, 15, 15), smoothUnorm16(255));
  EXPECT_EQ(at(17, 17, 15), smoothUnorm16(255));
  EXPECT_EQ(at(16, 16, 16), 0);
}

// slotDifference: the changed texels per 10³ block of the slot; a transmittance change counts
// as weighted only with a non-zero density among its 3³ neighbours (diagonals included).
TEST(BrickPoolSlot, DifferenceBoxesTheChangedTexelsAndWeighsLightByNearbyDensity) {
  constexpr int S = BrickPool::kSlotTexels;
  auto texel = [](std::vector<uint8_t>& slot, glm::ivec3 t) {
    return &slot[BrickPool::kTexelBytes * size_t((t.z * S + t.y) * S + t.x)];
  };
  std::vector<uint8_t> before(BrickPool::kSlotBytes, 0), now;
  for (size_t i = 0; i < before.size(); i += BrickPool::kTexelBytes) before[i + 1] = 200;
  std::vector<BrickPool::SlotChange> out;
  slotDifference(before.data(), before.data(), &out);
  EXPECT_TRUE(out.empty());
  // Density at (13,13,13) in both; light changes at its diagonal neighbour (12,12,12) and at
  // (12,16,12), three texels from any density; density changes at (3,4,5).
  texel(before, {13, 13, 13})[0] = 9;
  now = before;
  texel(now, {12, 12, 12})[1] = 100;
  texel(now, {12, 16, 12})[1] = 100;
  texel(now, {3, 4, 5})[0] = 1;
  slotDifference(before.data(), now.data(), &out);
  ASSERT_EQ(out.size(), 2u);  // blocks (0,0,0) and (1,1,1)
  EXPECT_EQ(out[0].bytes, (VoxelBox{{3, 4, 5}, {4, 5, 6}}));
  EXPECT_EQ(out[0].weighted, out[0].bytes);
  EXPECT_EQ(out[1].bytes, (VoxelBox{{12, 12, 12}, {13, 17, 13}}));
  EXPECT_EQ(out[1].weighted, (VoxelBox{{12, 12, 12}, {13, 13, 13}}));
  // Without the density, neither light change is weighted (the block is still reported).
  texel(before, {13, 13, 13})[0] = 0;
  texel(now, {13, 13, 13})[0] = 0;
  out.clear();
  slotDifference(before.data(), now.data(), &out);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_TRUE(out[1].weighted.empty());
  EXPECT_EQ(out[1].bytes, (VoxelBox{{12, 12, 12}, {13, 17, 13}}));
}

// The changes `st` (a sync from `old_volume` / `old_light` to `v` / the renderer's light)
// reports are exactly the texels whose bytes changed: every texel that packs differently lies in
// a box of its slot, and each box's faces hold changed texels (tight). `had_slot`: the bricks
// with a slot before (the others read the empty slot).
void expectChangesAreTheChangedTexels(const VolumeRenderer& renderer, const Volume& old_volume,
                                      const LightVolume& old_light, const BrickSet& had_slot,
                                      const Volume& v, const SyncStats& st) {
  constexpr int S = BrickPool::kSlotTexels;
  std::vector<uint8_t> a(BrickPool::kSlotBytes), b(BrickPool::kSlotBytes);
  std::vector<uint16_t> sa(BrickPool::kSmoothSlotBytes / 2), sb(BrickPool::kSmoothSlotBytes / 2);
  const glm::ivec3 d = v.brickDims();
  int changed_slots = 0;
  long changed_texels = 0;
  for (int z = 0; z < d.z; ++z)
    for (int y = 0; y < d.y; ++y)
      for (int x = 0; x < d.x; ++x) {
        const glm::ivec3 brick(x, y, z);
        if (!renderer.brickPool().slotOf(brick).w) continue;
        // What rays read there before: the slot's bytes, or the empty slot (density 0,
        // transmittance 1) for a brick that had none.
        packBrickSlot(old_volume, old_light, brick, a.data());
        packSmoothSlot(old_volume, brick, sa.data());
        if (!had_slot.count({x, y, z})) {
          for (size_t i = 0; i < a.size(); i += 2) a[i] = 0, a[i + 1] = 255;  // (d, T) twice
          std::fill(sa.begin(), sa.end(), 0);
        }
        packBrickSlot(v, renderer.lightVolume(), brick, b.data());
        packSmoothSlot(v, brick, sb.data());
        // A texel reads differently when its density, light or smoothed density changed.
        auto differs = [&](size_t texel) {
          const size_t o = BrickPool::kTexelBytes * texel;
          return a[o] != b[o] || a[o + 1] != b[o + 1] || sa[2 * texel] != sb[2 * texel];
        };
        std::vector<VoxelBox> boxes;
        for (const BrickPool::SlotChange& c : st.changes)
          if (c.brick == brick) boxes.push_back(c.bytes);
        bool any = false;
        for (int k = 0; k < S; ++k)
          for (int j = 0; j < S; ++j)
            for (int i = 0; i < S; ++i) {
              if (!differs(size_t((k * S + j) * S + i))) continue;
              any = true;
              ++changed_texels;
              const glm::ivec3 voxel = glm::min(brick * 16 + glm::ivec3(i, j, k), v.dims() - 1);
              EXPECT_TRUE(std::any_of(boxes.begin(), boxes.end(),
                                      [&](const VoxelBox& box) { return box.contains(voxel); }))
                  << "slot " << x << "," << y << "," << z << " texel " << i << "," << j << "," << k;
            }
        changed_slots += any;
        if (!any) {
          EXPECT_TRUE(boxes.empty()) << "slot " << x << "," << y << "," << z;
        }
        for (const VoxelBox& box : boxes) {
          // Tight: a texel on each face of the box changed.
          for (int axis = 0; axis < 3; ++axis)
            for (int face : {box.lo[axis], box.hi[axis] - 1}) {
              bool found = false;
              for (int k = box.lo.z; k < box.hi.z && !found; ++k)
                for (int j = box.lo.y; j < box.hi.y && !found; ++j)
                  for (int i = box.lo.x; i < box.hi.x && !found; ++i) {
                    const glm::ivec3 t = glm::ivec3(i, j, k) - brick * 16;
                    found = glm::ivec3(i, j, k)[axis] == face &&
                            differs(size_t((t.z * S + t.y) * S + t.x));
                  }
              EXPECT_TRUE(found) << "a loose box in slot " << x << "," << y << "," << z;
            }
        }
      }
  std::printf("%d slots, %ld texels changed; %zu boxes reported\n", changed_slots, changed_texels,
              st.changes.size());
  // Every slot reported changed somewhere (an added slot may hold what the empty slot held: it is
  // uploaded, not reported).
  BrickSet reported;
  for (const BrickPool::SlotChange& c : st.changes)
    reported.insert({c.brick.x, c.brick.y, c.brick.z});
  EXPECT_EQ(size_t(changed_slots), reported.size());
  EXPECT_LE(changed_slots, st.slots_uploaded);
}

class BrickPoolTest : public ::testing::Test {
 protected:
  void SetUp() override {
    CB_REQUIRE_GL();
    std::string err;
    ASSERT_TRUE(renderer.init(&err)) << err;
    // The smoothed companion kept from the first sync, as after an iso-surface style's frame
    // (TheSmoothedCompanionIsMadeAtTheFirstIsoSurfaceFrame checks that path).
    renderer.brickPool().enableSmooth(Volume(glm::ivec3(16)));
  }
  VolumeRenderer renderer;
};

TEST_F(BrickPoolTest, EveryBrickThatCanReadDensityHasASlotAndNoOtherDoes) {
  Volume v(glm::ivec3(96));
  paintBall(v, {30, 40, 50}, 9);
  paintBall(v, {80, 15, 17}, 6);
  v.set(47, 47, 47, 0.5f);  // one voxel at a brick's high corner: its neighbours read it
  renderer.sync(v, Light{});
  const BrickPool& pool = renderer.brickPool();
  const BrickSet slots = bricksWithSlots(pool);
  EXPECT_EQ(slots.size(), pool.slotsInUse());
  const glm::ivec3 d = v.brickDims();
  for (int z = 0; z < d.z; ++z)
    for (int y = 0; y < d.y; ++y)
      for (int x = 0; x < d.x; ++x) {
        const glm::ivec3 b(x, y, z);
        // Necessary: a slot wherever a voxel the slot holds (16b on) holds density.
        bool reads_density = false;
        const VoxelBox covered =
            VoxelBox{b * 16, b * 16 + BrickPool::kSlotTexels}.intersect(v.bounds());
        for (int k = covered.lo.z; k < covered.hi.z && !reads_density; ++k)
          for (int j = covered.lo.y; j < covered.hi.y && !reads_density; ++j)
            for (int i = covered.lo.x; i < covered.hi.x && !reads_density; ++i)
              reads_density = v.at(i, j, k) != 0.0f;
        // Sufficient: only where a brick of b + {0,1}³ is allocated.
        bool allocated_near = false;
        for (int n = 0; n < 8; ++n) {
          const glm::ivec3 c = b + glm::ivec3(n & 1, (n >> 1) & 1, n >> 2);
          if (glm::all(glm::lessThan(c, d)) && v.brick(c)) allocated_near = true;
        }
        const bool has = slots.count({x, y, z}) != 0;
        if (reads_density) {
          EXPECT_TRUE(has) << x << "," << y << "," << z;
        }
        EXPECT_EQ(has, allocated_near) << x << "," << y << "," << z;
      }
  // The corner voxel (47,47,47) lies in brick (2,2,2) and is read by the slots of (1..2)³.
  for (int n = 0; n < 8; ++n)
    EXPECT_TRUE(slots.count({1 + (n & 1), 1 + ((n >> 1) & 1), 1 + (n >> 2)}));
}

TEST_F(BrickPoolTest, AnEditUploadsOnlyTheSlotsAroundItsBricksAndItsShadow) {
  Volume v(glm::ivec3(128));
  paintBall(v, {40, 60, 40}, 14);
  paintBall(v, {100, 30, 90}, 10);
  Light light;
  renderer.sync(v, light);
  const size_t before = renderer.brickPool().slotsInUse();
  const std::vector<glm::ivec3> changed_before = v.changedBricksSince(v.generation());
  EXPECT_TRUE(changed_before.empty());
  const uint64_t generation = v.generation();
  const LightVolume old_light = renderer.lightVolume();
  v.set(45, 62, 41, 0.25f);  // inside the first ball
  const std::vector<glm::ivec3> changed = v.changedBricksSince(generation);
  ASSERT_EQ(changed.size(), 1u);
  SyncStats st = renderer.sync(v, light);
  // Expected: the slots reading the voxel whose density changed (slot b's main texels hold
  // voxels 16b … 16b + 19, its smoothed companion reads 16b − 1 … 16b + 20), and the slots
  // holding a voxel whose light changed in 8 bits, found here by comparing every voxel's light.
  const BrickPool& pool = renderer.brickPool();
  const LightVolume& new_light = renderer.lightVolume();
  BrickSet expected, expected_light;
  auto expect = [&](glm::ivec3 b, BrickSet* set) {
    if (glm::all(glm::greaterThanEqual(b, glm::ivec3(0))) && pool.slotOf(b).w)
      set->insert({b.x, b.y, b.z});
  };
  const glm::ivec3 edited(45, 62, 41);
  for (int n = 0; n < 27; ++n) {
    const glm::ivec3 b = changed[0] + glm::ivec3(n % 3, n / 3 % 3, n / 9) - 1;
    if (VoxelBox{b * 16 - 1, b * 16 + BrickPool::kSlotTexels + 1}.contains(edited))
      expect(b, &expected);
  }
  EXPECT_LT(expected.size(), 27u) << "every slot around the brick reads the voxel";
  const glm::ivec3 d = v.brickDims();
  long light_changed = 0;
  for (int z = 0; z < v.dims().z; ++z)
    for (int y = 0; y < v.dims().y; ++y)
      for (int x = 0; x < v.dims().x; ++x) {
        if (unorm8(old_light.at(x, y, z)) == unorm8(new_light.at(x, y, z))) continue;
        ++light_changed;
        const glm::ivec3 p(x, y, z);
        const glm::ivec3 hi = p >> 4, lo = glm::max((p - BrickPool::kSlotTexels + 1 + 15) >> 4, 0);
        for (int k = lo.z; k <= hi.z; ++k)
          for (int j = lo.y; j <= hi.y; ++j)
            for (int i = lo.x; i <= hi.x; ++i) expect({i, j, k}, &expected_light);
      }
  EXPECT_GT(light_changed, 0) << "the edit should change its shadow in 8 bits";
  // Fewer than the slots meeting the light box (what was re-packed before the sweep reported
  // its 8-bit changes).
  size_t in_light_box = 0;
  for (int z = 0; z < d.z; ++z)
    for (int y = 0; y < d.y; ++y)
      for (int x = 0; x < d.x; ++x) {
        const glm::ivec3 b(x, y, z);
        in_light_box +=
            pool.slotOf(b).w &&
            !VoxelBox{b * 16, b * 16 + BrickPool::kSlotTexels}.intersect(st.light_box).empty();
      }
  std::printf("re-packed %d slots; %zu meet the light box\n",
              st.slots_uploaded + st.slots_unchanged, in_light_box);
  EXPECT_LT(expected_light.size(), in_light_box);
  expected.insert(expected_light.begin(), expected_light.end());
  // Re-packed: exactly those; uploaded: those whose bytes changed (a slot reading a changed
  // brick where its own texels did not change is re-packed, not uploaded).
  EXPECT_EQ(size_t(st.slots_uploaded + st.slots_unchanged), expected.size());
  EXPECT_GT(st.slots_uploaded, 0);
  EXPECT_LT(size_t(st.slots_uploaded), before / 2) << "an edit re-uploads most of the pool";
  EXPECT_EQ(pool.slotsInUse(), before);
  EXPECT_FALSE(st.pool_grew);
  // An idle sync uploads nothing.
  EXPECT_EQ(renderer.sync(v, light).slots_uploaded, 0);
}

// The slots (held by `pool`) that hold a voxel whose 8-bit light differs between two light
// volumes, found by comparing every voxel.
BrickSet slotsReadingChangedLight(const BrickPool& pool, const Volume& v, const LightVolume& a,
                                  const LightVolume& b) {
  BrickSet slots;
  for (int z = 0; z < v.dims().z; ++z)
    for (int y = 0; y < v.dims().y; ++y)
      for (int x = 0; x < v.dims().x; ++x) {
        if (unorm8(a.at(x, y, z)) == unorm8(b.at(x, y, z))) continue;
        const glm::ivec3 p(x, y, z);
        const glm::ivec3 hi = p >> 4, lo = glm::max((p - BrickPool::kSlotTexels + 1 + 15) >> 4, 0);
        for (int k = lo.z; k <= hi.z; ++k)
          for (int j = lo.y; j <= hi.y; ++j)
            for (int i = lo.x; i <= hi.x; ++i)
              if (pool.slotOf({i, j, k}).w) slots.insert({i, j, k});
      }
  return slots;
}

void expectPoolIsAFreshPack(const VolumeRenderer& renderer, const Volume& v, const char* after);

// A light change re-packs only the slots holding a voxel whose 8-bit light changed (the light
// volume's per-brick byte hashes name the bricks, LightVolume::byte_hash), not every slot; a
// slot in full light or deep in shadow keeps its bytes. Small steps (a drag) and a large turn;
// after each the pool holds exactly a fresh pack.
TEST_F(BrickPoolTest, ALightChangeRepacksOnlyTheSlotsWhoseLightBytesChanged) {
  Volume v(glm::ivec3(128));
  paintBall(v, {40, 60, 40}, 14);
  paintBall(v, {100, 30, 90}, 10);
  paintBall(v, {64, 100, 64}, 8, 0.3f);
  Light light;
  renderer.sync(v, light);
  const BrickPool& pool = renderer.brickPool();
  const size_t in_use = pool.slotsInUse();
  const glm::vec3 towards[] = {{3.0f, 4.0f, 1.6f}, {3.1f, 4.0f, 1.7f}, {-3.0f, 2.0f, 1.0f}};
  for (const glm::vec3 p : towards) {
    const LightVolume old_light = renderer.lightVolume();
    light.direction = Light::directionTowards(p);
    const SyncStats st = renderer.sync(v, light);
    EXPECT_TRUE(st.light_moved);
    const BrickSet expected = slotsReadingChangedLight(pool, v, old_light, renderer.lightVolume());
    std::printf(
        "light towards (%.1f, %.1f, %.1f): %d slots re-packed (%d unchanged) of %zu; "
        "%zu hold a changed light byte\n",
        p.x, p.y, p.z, st.slots_uploaded + st.slots_unchanged, st.slots_unchanged, in_use,
        expected.size());
    // Re-packed: the slots of the bricks whose hashes changed, which hold a changed byte (each
    // brick's parts are hashed apart, so a slot below reads a changed part); unchanged among
    // them only by a byte the slot's apron does not hold.
    EXPECT_EQ(size_t(st.slots_uploaded), expected.size());
    EXPECT_LT(size_t(st.slots_uploaded + st.slots_unchanged), in_use)
        << "every slot re-packed: light in full sun or deep shadow kept its bytes";
    EXPECT_EQ(pool.slotsInUse(), in_use);
    expectPoolIsAFreshPack(renderer, v, "a light change");
  }
}

// The changes a sync reports are the texels whose bytes changed, read back from the pool, for an
// edit and its shadow.
TEST_F(BrickPoolTest, ReportedChangesAreExactlyTheTexelsThatChanged) {
  Volume v(glm::ivec3(96));
  paintBall(v, {40, 60, 40}, 12);
  paintBall(v, {44, 30, 42}, 10);  // below the first: in its shadow
  const Light light;
  renderer.sync(v, light);
  const Volume old_volume = v;
  const LightVolume old_light = renderer.lightVolume();
  const BrickSet had_slot = bricksWithSlots(renderer.brickPool());
  paintBall(v, {47, 62, 30}, 6);  // at the first ball's edge; its shadow falls on the second
  const SyncStats st = renderer.sync(v, light);
  ASSERT_FALSE(st.changes.empty());
  expectChangesAreTheChangedTexels(renderer, old_volume, old_light, had_slot, v, st);
}

// A light change in a brick's first voxels (x, z < 4) only, under a sun straight above: the
// slots one brick below on x and z hold those voxels too and must be re-packed (the sweep's
// LightByteChanges::Brick::readers), though nothing else near them changed.
TEST_F(BrickPoolTest, ALightChangeInABricksFirstVoxelsReachesTheSlotsBelow) {
  Volume v(glm::ivec3(64));
  paintBall(v, {20, 16, 20}, 6);  // the receiver, below
  Light light;
  light.direction = glm::vec3(0.0f, 1.0f, 0.0f);
  renderer.sync(v, light);
  const Volume old_volume = v;
  const LightVolume old_light = renderer.lightVolume();
  const BrickSet had_slot = bricksWithSlots(renderer.brickPool());
  v.set(17, 40, 17, 1.0f);  // one voxel above it, in brick (1, 2, 1)'s first voxels on x and z
  const SyncStats st = renderer.sync(v, light);
  ASSERT_FALSE(st.changes.empty());
  expectChangesAreTheChangedTexels(renderer, old_volume, old_light, had_slot, v, st);
}

TEST_F(BrickPoolTest, ReleasedSlotsAreReusedAndThePoolGrowsOnlyWhenFull) {
  Volume v(glm::ivec3(128));
  paintBall(v, {40, 40, 40}, 20);
  renderer.sync(v, Light{});
  const BrickPool& pool = renderer.brickPool();
  const size_t used = pool.slotsInUse();
  const size_t capacity = pool.slotCapacity();
  ASSERT_GT(used, 20u);
  eraseBox(v, v.bounds());
  SyncStats st = renderer.sync(v, Light{});
  EXPECT_EQ(pool.slotsInUse(), 0u);
  EXPECT_EQ(pool.slotCapacity(), capacity);
  // The same ball elsewhere (equally placed in its bricks) takes the freed slots: no growth.
  paintBall(v, {88, 72, 88}, 20);
  st = renderer.sync(v, Light{});
  EXPECT_FALSE(st.pool_grew);
  EXPECT_EQ(pool.slotsInUse(), used);
  EXPECT_EQ(pool.slotCapacity(), capacity);
  // Twice as much cloud does not fit: the pool grows, once.
  paintBall(v, {40, 40, 40}, 20);
  paintBall(v, {40, 90, 95}, 20);
  st = renderer.sync(v, Light{});
  EXPECT_TRUE(st.pool_grew);
  EXPECT_GT(pool.slotCapacity(), capacity);
  EXPECT_EQ(pool.slotsInUse(), bricksWithSlots(pool).size());
}

// A fresh volume gets a pool of the size it needs: after a big cloud, a new small one (the kiosk's
// empty sky after a visit) does not keep the big cloud's texture, and renders as a fresh
// renderer does; the same volume again keeps its pool.
TEST_F(BrickPoolTest, AFreshVolumeGetsAPoolSizedForItNotTheLargestSoFar) {
  Volume small(glm::ivec3(128));
  paintBall(small, {40, 40, 40}, 6);
  Light light;
  renderer.sync(small, light);
  const BrickPool& pool = renderer.brickPool();
  const size_t small_bytes = pool.poolBytes();
  Volume big = makeSparsePuffs(glm::ivec3(128), 4);
  paintBall(big, {64, 64, 64}, 40);
  EXPECT_TRUE(renderer.sync(big, light).pool_grew);
  const size_t big_bytes = pool.poolBytes();
  ASSERT_GT(big_bytes, 4 * small_bytes);
  // The same big volume, edited: the pool stays.
  paintBall(big, {100, 30, 100}, 5);
  renderer.sync(big, light);
  EXPECT_EQ(pool.poolBytes(), big_bytes);
  // Another small volume: back to a small pool, the one a fresh renderer makes for it.
  Volume next(glm::ivec3(128));
  paintBall(next, {90, 70, 30}, 6);
  renderer.sync(next, light);
  EXPECT_LT(4 * pool.poolBytes(), big_bytes);
  EXPECT_EQ(renderer.gpuMemory().pool, pool.poolBytes());
  EXPECT_EQ(pool.slotsInUse(), bricksWithSlots(pool).size());
  const Camera camera = Camera::reference().orbited(20.0f);
  VolumeRenderer fresh;
  std::string err;
  ASSERT_TRUE(fresh.init(&err)) << err;
  fresh.brickPool().enableSmooth(next);  // as the fixture's renderer
  fresh.sync(next, light);
  EXPECT_EQ(pool.poolBytes(), fresh.brickPool().poolBytes());
  ASSERT_EQ(render(renderer, camera).pixels, render(fresh, camera).pixels);
  // It grows again as the new cloud does.
  paintBall(next, {64, 64, 64}, 40);
  EXPECT_TRUE(renderer.sync(next, light).pool_grew);
  EXPECT_GT(pool.poolBytes(), small_bytes);
  fresh.sync(next, light);
  ASSERT_EQ(render(renderer, camera).pixels, render(fresh, camera).pixels);
}

// The pool after any sequence of edits (allocation, release, reuse, growth, light changes) holds
// what a fresh upload of the same volume holds: the images are identical.
TEST_F(BrickPoolTest, IncrementalUpdatesRenderExactlyLikeAFreshUpload) {
  Volume v(glm::ivec3(128));
  paintBall(v, {30, 30, 30}, 6);
  Light light;
  const Camera camera = Camera::reference().orbited(35.0f);
  renderer.sync(v, light);
  bool grew = false;
  auto step = [&](const char* what) {
    grew |= renderer.sync(v, light).pool_grew;
    VolumeRenderer fresh;
    std::string err;
    ASSERT_TRUE(fresh.init(&err)) << err;
    fresh.sync(v, light);
    const ImageRgba8 a = render(renderer, camera), b = render(fresh, camera);
    ASSERT_EQ(a.pixels, b.pixels) << "after " << what;
  };
  paintBall(v, {64, 64, 64}, 18);
  step("a ball in the middle");
  v = makeSparsePuffs(glm::ivec3(128), 4);
  step("another volume");
  eraseBox(v, {{48, 48, 48}, {80, 80, 80}});
  step("erasing its core");
  paintBall(v, {20, 100, 30}, 24);
  paintBall(v, {110, 20, 100}, 16);
  step("two more balls");
  light.direction = Light::directionTowards(glm::vec3(2.0f, 3.0f, -1.0f));
  step("a light change");
  eraseBox(v, {{0, 80, 0}, {64, 128, 64}});
  paintBall(v, {64, 64, 64}, 10, 0.6f);
  step("erase and repaint");
  EXPECT_TRUE(grew) << "the sequence should have grown the pool at least once";
}

// Every slot's texels and smoothed texels as the pool holds them equal a fresh pack of the
// volume and the light it was given (packBrickSlot, packSmoothSlot; the empty slot for a brick
// without one), after each of many small random edits, painted or erased, near brick corners
// and faces (where a change reaches the neighbours' slots or only their companions).
void expectPoolIsAFreshPack(const VolumeRenderer& renderer, const Volume& v, const char* after) {
  const BrickPool& pool = renderer.brickPool();
  constexpr int S = BrickPool::kSlotTexels;
  std::vector<uint8_t> held(BrickPool::kSlotBytes), packed(BrickPool::kSlotBytes);
  std::vector<uint16_t> held_smooth(S * S * S * 2), packed_smooth(S * S * S * 2);
  const glm::ivec3 d = v.brickDims();
  int mismatched = 0;
  for (int z = 0; z < d.z; ++z)
    for (int y = 0; y < d.y; ++y)
      for (int x = 0; x < d.x; ++x) {
        const glm::ivec3 b(x, y, z), at = glm::ivec3(pool.slotOf(b)) * S;
        glGetTextureSubImage(pool.poolTexture(), 0, at.x, at.y, at.z, S, S, S, GL_RGBA,
                             GL_UNSIGNED_BYTE, GLsizei(held.size()), held.data());
        glGetTextureSubImage(pool.smoothTexture(), 0, at.x, at.y, at.z, S, S, S, GL_RG,
                             GL_UNSIGNED_SHORT, GLsizei(held_smooth.size() * 2),
                             held_smooth.data());
        if (pool.slotOf(b).w) {
          packBrickSlot(v, renderer.lightVolume(), b, packed.data());
          packSmoothSlot(v, b, packed_smooth.data());
        } else {
          for (size_t i = 0; i < packed.size(); i += 2) packed[i] = 0, packed[i + 1] = 255;
          std::fill(packed_smooth.begin(), packed_smooth.end(), 0);
        }
        const bool same = held == packed && held_smooth == packed_smooth;
        if (!same && ++mismatched <= 5)
          ADD_FAILURE() << "after " << after << ": slot of brick " << x << "," << y << "," << z
                        << (held == packed ? " (smoothed texels)" : " (main texels)");
      }
  EXPECT_EQ(mismatched, 0) << "after " << after;
}

// The thesis and physical styles never read the companion: a renderer makes it at the first
// frame of a style that does (cartoon here), packed for every slot then, and keeps it from then.
TEST(BrickPoolCompanion, TheSmoothedCompanionIsMadeAtTheFirstIsoSurfaceFrame) {
  CB_REQUIRE_GL();
  VolumeRenderer r;
  std::string err;
  ASSERT_TRUE(r.init(&err)) << err;
  Volume v(glm::ivec3(64, 48, 64));
  paintBall(v, {30, 20, 34}, 12);
  const Light light;
  r.sync(v, light);
  const Camera camera = Camera::reference().orbited(35.0f);
  render(r, camera);
  EXPECT_EQ(r.brickPool().smoothTexture(), 0u) << "made for the thesis style";
  paintBall(v, {40, 30, 20}, 6);
  r.sync(v, light);
  const size_t main_bytes = r.brickPool().poolBytes();
  EXPECT_EQ(main_bytes, size_t(r.brickPool().slotCapacity()) * BrickPool::kSlotBytes);
  RenderOptions cartoon;
  cartoon.style = RenderStyle::kCartoon;
  render(r, camera, cartoon);
  ASSERT_NE(r.brickPool().smoothTexture(), 0u);
  EXPECT_EQ(r.brickPool().poolBytes(), 2 * main_bytes);  // RGBA8 + RG16
  expectPoolIsAFreshPack(r, v, "the first cartoon frame");
  eraseBox(v, {{24, 14, 28}, {33, 23, 37}});
  r.sync(v, light);
  expectPoolIsAFreshPack(r, v, "an erase after it");
}

TEST_F(BrickPoolTest, AfterRandomSmallEditsThePoolIsAFreshPackTexelForTexel) {
  uint32_t seed = 20261129;
  if (const char* env = std::getenv("CB_TEST_SEED")) seed = uint32_t(std::stoul(env));
  std::printf("seed %u (CB_TEST_SEED)\n", seed);
  std::mt19937 rng(seed);
  Volume v(glm::ivec3(64, 48, 64));
  paintBall(v, {30, 20, 34}, 12);
  const Light light;
  renderer.sync(v, light);
  expectPoolIsAFreshPack(renderer, v, "the first sync");
  auto pick = [&](int n) { return int(rng() % uint32_t(n)); };
  for (int step = 0; step < 40; ++step) {
    // A corner of a box 1–4 voxels wide at a brick's low or high face (or anywhere), per axis.
    glm::ivec3 lo;
    for (int a = 0; a < 3; ++a) {
      const int brick = pick(v.dims()[a] / 16);
      const int offsets[] = {-2, -1, 0, 1, 14, 15, 16, 17, 3, 8};
      lo[a] = std::clamp(brick * 16 + offsets[pick(10)] + (pick(4) == 0 ? pick(16) : 0), 0,
                         v.dims()[a] - 1);
    }
    const glm::ivec3 size(1 + pick(4), 1 + pick(4), 1 + pick(4));
    const VoxelBox box = VoxelBox{lo, lo + size}.intersect(v.bounds());
    const bool erase = pick(3) == 0;
    if (erase) {
      eraseBox(v, box);
    } else {
      const float density = float(1 + pick(255)) / 255.0f;
      for (int z = box.lo.z; z < box.hi.z; ++z)
        for (int y = box.lo.y; y < box.hi.y; ++y)
          for (int x = box.lo.x; x < box.hi.x; ++x) v.set(x, y, z, density);
    }
    // Sometimes two edits or more before a sync (the pool reads the union of their boxes).
    if (step < 39 && pick(4) == 0) continue;
    char what[96];
    std::snprintf(what, sizeof what, "step %d: %s (%d,%d,%d)+(%d,%d,%d)", step,
                  erase ? "erase" : "paint", lo.x, lo.y, lo.z, size.x, size.y, size.z);
    renderer.sync(v, light);
    expectPoolIsAFreshPack(renderer, v, what);
    if (HasFailure()) break;
  }
}

// A cloud painted in the far corner of a wide sky renders as the same cloud painted in the
// middle does (camera moved with it): the sun is a direction and the sky around is empty. At
// 512×128×512 (16× today's area at today's voxel size), not the 1024×256×1024 default: the light
// volume is still dense (268 MB here, 2 GB there) until the sparse light lands.
TEST_F(BrickPoolTest, ACloudInTheFarCornerOfAWideSkyRendersLikeOneInTheMiddle) {
  const glm::ivec3 dims(512, 128, 512);
  const glm::vec3 lo(-2.0f, -0.5f, -2.0f), hi(2.0f, 0.5f, 2.0f);
  Light light;
  light.direction = Light::directionTowards(glm::vec3(-4.0f, 2.0f, 2.5f));
  auto renderBallAt = [&](glm::ivec3 centre) {
    Volume v(dims, lo, hi);
    paintBall(v, centre, 14);
    paintBall(v, centre + glm::ivec3(10, 6, -4), 9);
    VolumeRenderer r;
    std::string err;
    EXPECT_TRUE(r.init(&err)) << err;
    r.sync(v, light);
    EXPECT_LT(r.brickPool().slotsInUse(), 64u);
    Camera camera = Camera::reference();
    const glm::vec3 target = v.voxelToWorld(glm::vec3(centre) + 0.5f);
    camera.eye = target + glm::vec3(0.35f, 0.25f, 0.35f);
    camera.target = target;
    return render(r, camera);
  };
  const ImageRgba8 corner = renderBallAt({490, 100, 490});
  const ImageRgba8 middle = renderBallAt({250, 60, 250});
  ImageRgba8 empty;
  {
    VolumeRenderer r;
    std::string err;
    ASSERT_TRUE(r.init(&err)) << err;
    r.sync(Volume(glm::ivec3(64)), light);
    empty = render(r, Camera::reference());
  }
  long long cloud = 0;
  double sum = 0;
  int worst = 0;
  for (size_t i = 0; i < corner.pixels.size(); ++i) {
    cloud += std::abs(int(corner.pixels[i]) - int(empty.pixels[i])) > 8;
    const int e = std::abs(int(corner.pixels[i]) - int(middle.pixels[i]));
    sum += e;
    worst = std::max(worst, e);
  }
  const double mean = sum / double(corner.pixels.size());
  std::printf("far corner vs middle: %lld cloud channels, mean error %.3f, worst %d (of 255)\n",
              cloud, mean, worst);
  EXPECT_GT(cloud, 3000) << "the far corner's cloud does not show";
  EXPECT_LT(mean, 0.1);
  EXPECT_LE(worst, 4);  // sample positions along the rays differ a little (they start at the box)
}

// An empty sky costs little on the GPU. The renderer's GL memory is counted in bytes;
// at 512×128×512 (16× today's area: the light volume beside it is still dense until the sparse
// light lands, 268 MB of CPU memory, so this test stays below the 1024×256×1024 default) and the
// pool's share at the 1024×256×1024 sky itself.
TEST_F(BrickPoolTest, AnEmptySkyCostsLittleOnTheGpu) {
  const glm::ivec3 dims(512, 128, 512);
  Volume v(dims, glm::vec3(-2.0f, -0.5f, -2.0f), glm::vec3(2.0f, 0.5f, 2.0f));
  renderer.sync(v, Light{});
  const RendererGpuMemory m = renderer.gpuMemory();
  std::printf(
      "empty %dx%dx%d sky, GL bytes: pool %zu, indirection %zu, occupancy %zu, ray "
      "bounds %zu (volume total %zu)\n",
      dims.x, dims.y, dims.z, m.pool, m.indirection, m.occupancy, m.ray_bounds, m.volume());
  EXPECT_EQ(renderer.brickPool().slotsInUse(), 0u);
  // The first pool: 3 × 3 × 1 slots of 20³ texels, RGBA8 and the RG16 smoothed companion.
  EXPECT_LE(m.pool, size_t(9 * 8000 * 8));
  EXPECT_EQ(m.indirection, size_t(32 * 8 * 32 * 4));
  EXPECT_LT(m.volume(), size_t(2) << 20);  // against 64 MiB for a dense RG8 texture

  // The 1024×256×1024 sky: the pool with its indirection table alone (an empty sky reads no
  // light, so an empty light volume stands in for it).
  BrickPool pool;
  const Volume sky(glm::ivec3(1024, 256, 1024));
  pool.update(sky, LightVolume{}, true, {}, {});
  std::printf("empty 1024x256x1024 sky: pool %zu bytes, indirection %zu bytes (dense RG8: %zu)\n",
              pool.poolBytes(), pool.indirectionBytes(), sky.voxelCount() * 2);
  EXPECT_LE(pool.poolBytes() + pool.indirectionBytes(), size_t(1) << 20);
}

}  // namespace
// Listed by slot (ChangeDetail::kSlots, an animation's frames): the slots texel by texel reports
// and the slots added, each whole (so covering every texel that changed in it); the pool the same.
TEST_F(BrickPoolTest, ChangesListedBySlotAreTheChangedSlotsWhole) {
  VolumeRenderer by_slot;
  std::string err;
  ASSERT_TRUE(by_slot.init(&err)) << err;
  by_slot.brickPool().enableSmooth(Volume(glm::ivec3(16)));
  Volume v(glm::ivec3(96));
  paintBall(v, {40, 60, 40}, 12);
  paintBall(v, {44, 30, 42}, 10);
  const Light light;
  renderer.sync(v, light);
  by_slot.sync(v, light, ChangeDetail::kSlots);
  const BrickSet had_slot = bricksWithSlots(by_slot.brickPool());
  paintBall(v, {47, 62, 30}, 6);  // at the first ball's edge; its shadow falls on the second
  const SyncStats texels = renderer.sync(v, light);
  const SyncStats slots = by_slot.sync(v, light, ChangeDetail::kSlots);
  ASSERT_FALSE(texels.changes.empty());
  BrickSet texel_bricks, slot_bricks;
  for (const BrickPool::SlotChange& c : texels.changes)
    texel_bricks.insert({c.brick.x, c.brick.y, c.brick.z});
  for (const BrickPool::SlotChange& c : slots.changes) {
    slot_bricks.insert({c.brick.x, c.brick.y, c.brick.z});
    // The whole slot: its brick and the high apron, clamped to the volume.
    const glm::ivec3 lo = c.brick * Volume::kBrickSize;
    EXPECT_EQ(c.bytes.lo, lo);
    EXPECT_EQ(c.bytes.hi, glm::min(lo + BrickPool::kSlotTexels, v.dims()));
    EXPECT_EQ(c.weighted, c.bytes);
  }
  // The same slots, and those added for the edit (texel by texel, an added slot holding what
  // the empty slot held is not reported; by slot it is, whole).
  for (const auto& b : texel_bricks) EXPECT_TRUE(slot_bricks.count(b));
  for (const auto& b : slot_bricks)
    EXPECT_TRUE(texel_bricks.count(b) || !had_slot.count(b)) << "an unchanged slot reported";
  EXPECT_EQ(slots.slots_uploaded, texels.slots_uploaded);
  expectPoolIsAFreshPack(by_slot, v, "a sync listing changes by slot");
}

}  // namespace cb
