// The brick pool renders what the dense volume texture rendered. The images
// in tests/golden/render/dense/ were written by the renderer as it was before the pool (one dense
// RG8 3D texture over the whole grid, main at adb0e86) with this same file and
// CB_WRITE_DENSE_REFERENCE=1; each case here must match its image within 1/255 in every channel
// of every pixel. The scenes are chosen to reach what the pool changes: 128³ volumes (8³ bricks,
// many of them empty), a grid that is no multiple of the 16-voxel brick (partial edge bricks),
// single voxels on brick corners and faces (trilinear footprints across bricks, sampled from an
// empty neighbour), the volume's faces (clamp to edge), every style's sample sites (the
// iso-surface's normal and inner-surface lookups, the physical style's noise coordinate), the
// march without skipping and a camera inside the cloud.
//
// Do not regenerate these with the pool: they are the dense path's record. If a deliberate change
// to the images makes them stale, regenerate with CB_WRITE_DENSE_REFERENCE=1, review, and say in
// the commit that they no longer come from the dense path. The iso-surface styles' images
// (cumulus128_ink_reference, _cartoon_side, _sketch_reference, puffs128_cartoon_reference) were
// so rewritten by the pool when the surface normal narrowed to 1 voxel and cartoon's inner line
// to two pixels (render_style.h isoSurfaceReach), and the cartoon and sketch images
// (brick_borders_cartoon, cumulus128_cartoon_side, cumulus128_sketch_reference,
// puffs128_cartoon_reference) again when the inner surface came to be read from the density
// smoothed over ~3 voxels (raycast.frag.glsl), and once more (cumulus128_cartoon_side,
// cumulus128_sketch_reference, puffs128_cartoon_reference: a few line pixels) when that density
// came from the pool's 16-bit smoothed companion instead of 8 reads of 8-bit filtered density;
// cumulus128_ink_reference again when ink drew its outline in image space from the blurred
// coverage (style_compose.frag.glsl), cumulus128_sketch_reference when the sketch's inner line
// took the cartoon's two-pixel width limit (a few line pixels) and again when the sketch drew its
// outline in image space from the blurred coverage (5916 channels, worst 158); the others are
// still the dense path's.
#include <cstdlib>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "app/render/image_io.h"
#include "app/render/render_target.h"
#include "app/render/volume_renderer.h"
#include "app/volume/scene_generators.h"
#include "tests/unit/render/gl_test_context.h"

namespace cb {
namespace {

constexpr int kW = 320, kH = 200;

std::string referencePath(const std::string& name) {
  return std::string(CB_SOURCE_DIR) + "/tests/golden/render/dense/" + name + ".png";
}

Light lightFromTheLeft() {
  Light l;
  l.direction = Light::directionTowards(glm::vec3(-4.0f, 2.0f, 2.5f));
  return l;
}

Light lowWarmLightFromTheRight() {
  Light l;
  l.direction = Light::directionTowards(glm::vec3(3.0f, 1.0f, -4.0f));
  l.colour = glm::vec3(1.0f, 0.85f, 0.7f);
  return l;
}

Camera sideView() {
  Camera camera = Camera::reference();
  camera.eye = glm::vec3(-2.4f, 0.4f, 1.9f);
  camera.target = glm::vec3(0.0f, 0.05f, 0.0f);
  return camera;
}

Camera topView() {
  Camera camera = Camera::reference();
  camera.eye = glm::vec3(0.3f, 2.9f, 0.4f);
  camera.target = glm::vec3(0.0f);
  return camera;
}

void expectMatchesDense(const std::string& name, const Volume& volume, const Light& light,
                        const Camera& camera, RenderOptions options = {}) {
  CB_REQUIRE_GL();
  VolumeRenderer renderer;
  std::string err;
  ASSERT_TRUE(renderer.init(&err)) << err;
  renderer.sync(volume, light);
  RenderTarget target;
  ASSERT_TRUE(target.create(kW, kH, RenderTarget::Format::kRgba8, &err)) << err;
  renderer.render(camera, kW, kH, target.fbo(), options);
  const ImageRgba8 image = target.readRgba8();
  if (std::getenv("CB_WRITE_DENSE_REFERENCE")) {
    std::filesystem::create_directories(std::filesystem::path(referencePath(name)).parent_path());
    writePng(referencePath(name), image);
    std::printf("wrote %s\n", referencePath(name).c_str());
    return;
  }
  ASSERT_TRUE(std::filesystem::exists(referencePath(name))) << "no image " << referencePath(name);
  const ImageRgba8 dense = readPng(referencePath(name));
  ASSERT_EQ(dense.width, kW);
  ASSERT_EQ(dense.height, kH);
  int worst = 0;
  long long differing = 0;
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    const int e = std::abs(int(image.pixels[i]) - int(dense.pixels[i]));
    worst = std::max(worst, e);
    differing += e != 0;
  }
  std::printf("%s: %lld channels differ, worst %d\n", name.c_str(), differing, worst);
  if (worst > 1) writePng(name + ".actual.png", image);
  EXPECT_LE(worst, 1) << name << ": worst channel error against the dense render (see " << name
                      << ".actual.png); " << differing << " channels differ";
  // The scene must show something, or matching it proves nothing.
  const ImageRgba8 empty_like = [&] {
    VolumeRenderer r;
    std::string e;
    EXPECT_TRUE(r.init(&e)) << e;
    r.sync(Volume(volume.dims(), volume.worldMin(), volume.worldMax()), light);
    RenderTarget t;
    EXPECT_TRUE(t.create(kW, kH, RenderTarget::Format::kRgba8, &e)) << e;
    r.render(camera, kW, kH, t.fbo(), options);
    return t.readRgba8();
  }();
  long long cloud_channels = 0;
  for (size_t i = 0; i < image.pixels.size(); ++i)
    cloud_channels += std::abs(int(image.pixels[i]) - int(empty_like.pixels[i])) > 8;
  EXPECT_GT(cloud_channels, 30) << name << ": the scene shows no cloud";
}

const Volume& cumulus128() {
  static const Volume v = makeBundledCumulus(glm::ivec3(128), 1);
  return v;
}

const Volume& puffs128() {
  static const Volume v = makeSparsePuffs(glm::ivec3(128), 2);
  return v;
}

RenderOptions styled(RenderStyle style) {
  RenderOptions o;
  o.style = style;
  return o;
}

TEST(DenseReference, CumulusReferenceView) {
  expectMatchesDense("cumulus128_reference", cumulus128(), lightFromTheLeft(), Camera::reference());
}

TEST(DenseReference, CumulusOrbited) {
  expectMatchesDense("cumulus128_orbit75", cumulus128(), lightFromTheLeft(),
                     Camera::reference().orbited(75.0f));
  expectMatchesDense("cumulus128_orbit200", cumulus128(), lowWarmLightFromTheRight(),
                     Camera::reference().orbited(200.0f));
}

TEST(DenseReference, CumulusFromAbove) {
  expectMatchesDense("cumulus128_top", cumulus128(), lightFromTheLeft(), topView());
}

TEST(DenseReference, CumulusEveryStyle) {
  expectMatchesDense("cumulus128_physical_side", cumulus128(), lowWarmLightFromTheRight(),
                     sideView(), styled(RenderStyle::kPhysical));
  expectMatchesDense("cumulus128_ink_reference", cumulus128(), lightFromTheLeft(),
                     Camera::reference(), styled(RenderStyle::kInk));
  expectMatchesDense("cumulus128_cartoon_side", cumulus128(), lightFromTheLeft(), sideView(),
                     styled(RenderStyle::kCartoon));
  expectMatchesDense("cumulus128_sketch_reference", cumulus128(), lowWarmLightFromTheRight(),
                     Camera::reference(), styled(RenderStyle::kSketch));
}

TEST(DenseReference, CameraInsideTheCumulus) {
  Camera camera;
  camera.eye = glm::vec3(0.05f, -0.1f, 0.1f);
  camera.target = glm::vec3(1.0f, 0.2f, 0.6f);
  camera.fov_y_deg = 60.0f;
  RenderOptions options;
  options.extinction_per_voxel = 0.05f;
  expectMatchesDense("cumulus128_inside", cumulus128(), Light{}, camera, options);
}

TEST(DenseReference, SparsePuffs) {
  expectMatchesDense("puffs128_reference", puffs128(), lightFromTheLeft(), Camera::reference());
  expectMatchesDense("puffs128_orbit120", puffs128(), lowWarmLightFromTheRight(),
                     Camera::reference().orbited(120.0f));
  expectMatchesDense("puffs128_top", puffs128(), lightFromTheLeft(), topView());
  expectMatchesDense("puffs128_cartoon_reference", puffs128(), lightFromTheLeft(),
                     Camera::reference(), styled(RenderStyle::kCartoon));
}

TEST(DenseReference, SparsePuffsWithoutSkipping) {
  RenderOptions options;
  options.skip_empty_space = false;
  expectMatchesDense("puffs128_noskip", puffs128(), lightFromTheLeft(),
                     Camera::reference().orbited(30.0f), options);
}

TEST(DenseReference, GridThatIsNoMultipleOfTheBrick) {
  const Volume v = makeSparsePuffs(glm::ivec3(100, 72, 90), 5);
  expectMatchesDense("puffs100x72x90_reference", v, lightFromTheLeft(), Camera::reference());
  expectMatchesDense("puffs100x72x90_orbit250", v, lowWarmLightFromTheRight(),
                     Camera::reference().orbited(250.0f));
}

// Dense voxels on brick corners, faces and the volume's faces: every trilinear footprint across
// bricks, including those sampled from an empty brick next to an occupied one.
TEST(DenseReference, VoxelsOnBrickBorders) {
  Volume v(glm::ivec3(64));
  const glm::ivec3 planted[] = {{15, 15, 15}, {16, 16, 16}, {31, 16, 47}, {47, 47, 15},
                                {32, 40, 31}, {0, 0, 0},    {63, 63, 63}, {48, 32, 63},
                                {63, 15, 0},  {8, 63, 16},  {31, 31, 32}, {16, 47, 48}};
  for (glm::ivec3 p : planted)
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const glm::ivec3 q = p + glm::ivec3(dx, dy, dz);
          if (glm::any(glm::lessThan(q, glm::ivec3(0))) ||
              glm::any(glm::greaterThanEqual(q, v.dims())))
            continue;
          v.set(q.x, q.y, q.z, dx == 0 && dy == 0 && dz == 0 ? 1.0f : 0.35f);
        }
  Camera close = Camera::reference();
  close.eye = glm::vec3(1.5f, 1.1f, 1.6f);
  expectMatchesDense("brick_borders_close", v, lightFromTheLeft(), close);
  expectMatchesDense("brick_borders_cartoon", v, lightFromTheLeft(),
                     Camera::reference().orbited(40), styled(RenderStyle::kCartoon));
}

}  // namespace
}  // namespace cb
