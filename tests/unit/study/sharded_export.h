// For the sharded study export tests (study_cli_test on one machine, study_slurm_export_test
// through a one-node Slurm): a study of recorded sessions listed in a manifest, and the
// byte-for-byte comparison of two export folders.
#pragma once

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <openvdb/openvdb.h>

#include "tests/support/reference_journal.h"

namespace cb::test {

// `count` session folders DIR/Pnn-20261129T0700nnZ/session.cbj (the runner's layout; session n
// paints the reference strokes n times over, so every session differs) and DIR/manifest.txt
// listing them relative to DIR, in order.
inline std::string writeShardedStudy(const std::filesystem::path& dir, int count) {
  std::ofstream manifest(dir / "manifest.txt");
  manifest << "# sessions of the sharded export test\n";
  for (int n = 1; n <= count; ++n) {
    char name[48];
    std::snprintf(name, sizeof name, "P%02d-20261129T0700%02dZ", n, n);
    std::filesystem::create_directories(dir / name);
    std::string error;
    EXPECT_TRUE(
        recordReferenceJournal((dir / name / "session.cbj").string(), 320, 180, 1 + n % 3, &error))
        << error;
    manifest << name << "/session.cbj\n";
  }
  return (dir / "manifest.txt").string();
}

// Every regular file under `root`, by its path relative to it, with its bytes.
inline std::map<std::string, std::string> filesUnder(const std::filesystem::path& root) {
  std::map<std::string, std::string> files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(root)) {
    if (!entry.is_regular_file()) continue;
    std::ifstream in(entry.path(), std::ios::binary);
    files[std::filesystem::relative(entry.path(), root).string()] =
        std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  return files;
}

// The density grid of an OpenVDB file as bytes: every active voxel's coordinate and value in the
// tree's order. (The file itself differs between two writes of the same grid: OpenVDB stamps
// each file with a fresh UUID.)
inline std::string vdbDensity(const std::filesystem::path& path) {
  openvdb::initialize();
  openvdb::io::File file(path.string());
  file.open();
  auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid("density"));
  file.close();
  std::string bytes;
  if (!grid) return bytes;
  for (auto it = grid->cbeginValueOn(); it; ++it) {
    const openvdb::Coord c = it.getCoord();
    const float v = *it;
    bytes.append(reinterpret_cast<const char*>(&c), sizeof c);
    bytes.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  return bytes;
}

// The two folders hold the same files with the same bytes (bit-identical: the merge is a join
// of the very bytes one run writes, and each shard replays its sessions as one run does, so
// there is no tolerance), `ignored` files aside; .vdb files by their density grid.
inline void expectSameExport(const std::filesystem::path& single,
                             const std::filesystem::path& merged,
                             const std::vector<std::string>& ignored = {}) {
  std::map<std::string, std::string> a = filesUnder(single), b = filesUnder(merged);
  for (const std::string& name : ignored) {
    a.erase(name);
    b.erase(name);
  }
  ASSERT_FALSE(a.empty());
  for (const auto& [name, bytes] : a) {
    const auto other = b.find(name);
    if (other == b.end()) {
      ADD_FAILURE() << name << " is missing from the merged export";
      continue;
    }
    if (name.size() > 4 && name.substr(name.size() - 4) == ".vdb") {
      EXPECT_TRUE(vdbDensity(single / name) == vdbDensity(merged / name))
          << name << "'s grid differs";
      continue;
    }
    EXPECT_TRUE(bytes == other->second)
        << name << " differs (" << bytes.size() << " vs " << other->second.size() << " bytes)";
  }
  for (const auto& [name, bytes] : b)
    EXPECT_TRUE(a.count(name)) << name << " is in the merged export only";
}

}  // namespace cb::test
