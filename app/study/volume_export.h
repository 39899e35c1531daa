// A volume as the files Blender, Houdini, numpy and R open: `<stem>.vdb` (OpenVDB fog volume, a
// FloatGrid named "density" placed on the volume's world box: app/volume/volume_vdb_file.h) and
// `<stem>.cbvol` (one JSON header line, then the raw little-endian float32 of the box holding
// the cloud, x fastest: app/volume/volume_file.h; reading it in numpy: app/study/README.md). The
// .vdb is skipped, with a note, in a build without OpenVDB.
#pragma once

#include <string>
#include <vector>

#include "app/volume/volume.h"

namespace cb {

struct VolumeExport {
  std::vector<std::string> written;  // paths in the order written
  std::string note;                  // why a file was skipped, else empty
};

// Creates `dir` if needed. Errors (VolumeFileError, VolumeVdbError, std::runtime_error) name the
// file.
VolumeExport exportVolume(const Volume& volume, const std::string& dir, const std::string& stem);

// True when this build writes .vdb files.
bool volumeExportHasVdb();

}  // namespace cb
