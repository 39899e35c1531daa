#include "app/study/volume_export.h"

#include <filesystem>
#include <stdexcept>
#include <system_error>

#include "app/volume/volume_file.h"
#if CB_STUDY_HAVE_VDB
#include "app/volume/volume_vdb_file.h"
#endif

namespace cb {

bool volumeExportHasVdb() {
  return CB_STUDY_HAVE_VDB != 0;
}

VolumeExport exportVolume(const Volume& volume, const std::string& dir, const std::string& stem) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw std::runtime_error(dir + ": cannot create the directory: " + ec.message());
  VolumeExport result;
  const std::filesystem::path base = std::filesystem::path(dir) / stem;
#if CB_STUDY_HAVE_VDB
  const std::string vdb = base.string() + ".vdb";
  saveVolumeVdb(volume, vdb);
  result.written.push_back(vdb);
#else
  result.note = "built without OpenVDB: " + base.string() + ".vdb not written";
#endif
  const std::string raw = base.string() + ".cbvol";
  saveVolume(volume, raw);
  result.written.push_back(raw);
  return result;
}

}  // namespace cb
