// Volume and render exports read back by OpenVDB, OpenEXR and libpng.
#include <cmath>
#include <filesystem>
#include <string>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <gtest/gtest.h>
#include <openvdb/openvdb.h>

#include "app/render/image_io.h"
#include "app/study/render_export.h"
#include "app/study/volume_export.h"
#include "app/volume/volume_file.h"
#include "app/volume/volume_vdb_file.h"

namespace cb {
namespace {

std::string tempDir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("cb_study_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  return dir.string();
}

// A volume with cubic voxels of 0.1 on an off-centre box, a density pattern that differs per
// voxel, and some zero voxels (which OpenVDB keeps inactive).
Volume patternVolume(size_t* nonzero) {
  Volume v(glm::ivec3(12, 10, 8), glm::vec3(-0.7f, 0.2f, -0.4f), glm::vec3(0.5f, 1.2f, 0.4f));
  *nonzero = 0;
  for (int z = 0; z < 8; ++z)
    for (int y = 0; y < 10; ++y)
      for (int x = 0; x < 12; ++x) {
        const float d = (x + y + z) % 3 == 0 ? 0.0f : 0.01f * float(x + 12 * y + 120 * z + 1);
        v.set(x, y, z, d);
        if (d != 0.0f) ++*nonzero;
      }
  return v;
}

TEST(StudyVolumeExport, VdbHasTheDensityFogGridWithValuesAndTransform) {
  size_t nonzero = 0;
  const Volume volume = patternVolume(&nonzero);
  const std::string dir = tempDir("vdb");
  const VolumeExport exported = exportVolume(volume, dir, "cloud");
  ASSERT_TRUE(volumeExportHasVdb());
  ASSERT_EQ(exported.written.size(), 2u);
  EXPECT_EQ(exported.written[0], dir + "/cloud.vdb");

  openvdb::initialize();
  openvdb::io::File file(dir + "/cloud.vdb");
  file.open();
  openvdb::GridBase::Ptr base = file.readGrid("density");
  file.close();
  auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(base);
  ASSERT_TRUE(grid) << "density is not a FloatGrid";
  EXPECT_EQ(grid->getGridClass(), openvdb::GRID_FOG_VOLUME);
  EXPECT_EQ(grid->activeVoxelCount(), openvdb::Index64(nonzero));
  auto accessor = grid->getConstAccessor();
  for (int z = 0; z < 8; ++z)
    for (int y = 0; y < 10; ++y)
      for (int x = 0; x < 12; ++x) {
        const openvdb::Coord ijk(x, y, z);
        ASSERT_EQ(accessor.getValue(ijk), volume.at(x, y, z)) << x << "," << y << "," << z;
        ASSERT_EQ(accessor.isValueOn(ijk), volume.at(x, y, z) != 0.0f);
      }
  const openvdb::Vec3d size = grid->voxelSize();
  EXPECT_NEAR(size.x(), 0.1, 1e-6);
  EXPECT_NEAR(size.y(), 0.1, 1e-6);
  EXPECT_NEAR(size.z(), 0.1, 1e-6);
  // Index (i,j,k) is the centre of our voxel (i,j,k): world_min + (ijk + ½)·size.
  for (const openvdb::Coord ijk :
       {openvdb::Coord(0, 0, 0), openvdb::Coord(11, 9, 7), openvdb::Coord(3, 5, 2)}) {
    const openvdb::Vec3d w = grid->indexToWorld(ijk);
    const glm::vec3 expected =
        volume.voxelToWorld(glm::vec3(ijk.x(), ijk.y(), ijk.z()) + glm::vec3(0.5f));
    EXPECT_NEAR(w.x(), expected.x, 1e-5);
    EXPECT_NEAR(w.y(), expected.y, 1e-5);
    EXPECT_NEAR(w.z(), expected.z, 1e-5);
  }
  // The active voxels' world bounding box is inside the volume's world box.
  const openvdb::CoordBBox active = grid->evalActiveVoxelBoundingBox();
  EXPECT_EQ(active.min(), openvdb::Coord(0, 0, 0));
  EXPECT_EQ(active.max(), openvdb::Coord(11, 9, 7));

  // The raw float32 + JSON file gives the same voxels back.
  const Volume raw = loadVolume(dir + "/cloud.cbvol");
  ASSERT_EQ(raw.dims(), volume.dims());
  EXPECT_EQ(raw.worldMin(), volume.worldMin());
  EXPECT_EQ(raw.worldMax(), volume.worldMax());
  {
    const std::vector<float> raw_dense = raw.toDense(), volume_dense = volume.toDense();
    for (size_t i = 0; i < volume.voxelCount(); ++i) ASSERT_EQ(raw_dense[i], volume_dense[i]);
  }
  std::filesystem::remove_all(dir);
}

TEST(StudyVolumeExport, NonCubicVoxelsAreRefusedNamingTheFile) {
  Volume v(glm::ivec3(4, 4, 4), glm::vec3(0.0f), glm::vec3(1.0f, 2.0f, 1.0f));
  const std::string dir = tempDir("noncubic");
  std::filesystem::create_directories(dir);
  try {
    saveVolumeVdb(v, dir + "/x.vdb");
    FAIL() << "non-cubic voxels were accepted";
  } catch (const VolumeVdbError& e) {
    EXPECT_NE(std::string(e.what()).find(dir + "/x.vdb"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("not cubic"), std::string::npos) << e.what();
  }
  std::filesystem::remove_all(dir);
}

// IEC 61966-2-1 decoding, written out here independently of render_export.cpp.
double srgbDecode(double c) {
  if (c <= 0.0) return 0.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

TEST(StudyRenderExport, ExrIsLinearLightAndPngIsTheDisplayFrame) {
  ImageRgbaF frame;
  frame.width = 7;
  frame.height = 5;
  for (int y = 0; y < frame.height; ++y)
    for (int x = 0; x < frame.width; ++x) {
      frame.pixels.push_back(float(x) / 6.0f);       // 0..1 across
      frame.pixels.push_back(float(y) / 4.0f);       // 0..1 down
      frame.pixels.push_back(0.03f);                 // in the linear toe
      frame.pixels.push_back(float(x + y) / 10.0f);  // coverage
    }
  const std::string dir = tempDir("render");
  const std::vector<std::string> written = exportRender(frame, dir, "task1");
  ASSERT_EQ(written.size(), 2u);

  Imf::InputFile exr(written[0].c_str());
  const Imath::Box2i window = exr.header().dataWindow();
  const int w = window.max.x - window.min.x + 1, h = window.max.y - window.min.y + 1;
  ASSERT_EQ(w, 7);
  ASSERT_EQ(h, 5);
  for (const char* channel : {"R", "G", "B", "A"}) {
    const Imf::Channel* c = exr.header().channels().findChannel(channel);
    ASSERT_NE(c, nullptr) << channel;
    EXPECT_EQ(c->type, Imf::FLOAT) << channel;
  }
  std::vector<float> rgba(size_t(w) * h * 4);
  Imf::FrameBuffer fb;
  const char* names[] = {"R", "G", "B", "A"};
  for (int c = 0; c < 4; ++c)
    fb.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(rgba.data() + c),
                                   sizeof(float) * 4, sizeof(float) * 4 * w));
  exr.setFrameBuffer(fb);
  exr.readPixels(window.min.y, window.max.y);
  for (size_t i = 0; i < rgba.size(); ++i) {
    const bool alpha = i % 4 == 3;
    const double expected = alpha ? frame.pixels[i] : srgbDecode(frame.pixels[i]);
    ASSERT_NEAR(rgba[i], expected, 1e-6) << "value " << i;
  }
  // Mid grey 0.5 on screen is 0.214 in linear light.
  EXPECT_NEAR(srgbToLinear(0.5f), 0.2140411f, 1e-6);

  const ImageRgba8 png = readPng(written[1]);
  ASSERT_EQ(png.width, 7);
  ASSERT_EQ(png.height, 5);
  for (size_t i = 0; i < png.pixels.size(); ++i)
    ASSERT_EQ(png.pixels[i], uint8_t(std::lround(frame.pixels[i] * 255.0f))) << "byte " << i;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace cb
