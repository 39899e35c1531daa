// cloudbrush-volume-to-vdb IN.cbvol OUT.vdb — writes a volume file as an OpenVDB fog volume
// (saveVolumeVdb: a FloatGrid named "density", GRID_FOG_VOLUME, same world placement), so
// Debian's vdb_render can render the same scene as `cloudbrush render` (used by
// `cloudbrush bench render`).
#include <cstdio>
#include <exception>

#include "app/volume/volume_file.h"
#include "app/volume/volume_vdb_file.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s IN.cbvol OUT.vdb\n", argv[0]);
    return 2;
  }
  try {
    cb::saveVolumeVdb(cb::loadVolume(argv[1]), argv[2]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cloudbrush-volume-to-vdb: %s\n", e.what());
    return 1;
  }
  return 0;
}
