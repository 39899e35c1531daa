#include "app/volume/volume_file.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <new>
#include <utility>
#include <vector>

namespace cb {
namespace {

static_assert(std::endian::native == std::endian::little,
              "volume files are little-endian; add byte swapping for this platform");

constexpr size_t kMaxHeaderBytes = 4096;

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;

// The volume the header describes; the allocation is the only one sized by the header, and
// happens only after the header's sizes were checked.
Volume allocate(const VolumeFileHeader& h, const std::string& name) {
  try {
    return Volume(glm::ivec3(int(h.dims[0]), int(h.dims[1]), int(h.dims[2])), h.world_min,
                  h.world_max);
  } catch (const std::bad_alloc&) {
    throw VolumeFileError(name, "header field 'dims': " + formatDims(h) + " voxels (" +
                                    std::to_string(h.data_bytes) + " bytes) do not fit in memory");
  }
}

// Refuses a non-finite density (`first_bad`: its dense index, or voxelCount() when there is
// none) and marks the whole volume changed.
Volume finish(Volume v, size_t first_bad, const std::string& name) {
  if (first_bad < v.voxelCount())
    throw VolumeFileError(name, "non-finite density at voxel index " + std::to_string(first_bad));
  v.markDirty(v.bounds());
  return v;
}

// Stores one row of voxels (x fastest) at (0, y, z), noting the first non-finite one.
void storeRow(Volume& v, int y, int z, const float* row, size_t* first_bad) {
  const int n = v.dims().x;
  if (*first_bad == v.voxelCount())
    for (int x = 0; x < n; ++x)
      if (!std::isfinite(row[x])) {
        *first_bad = v.index(x, y, z);
        break;
      }
  v.writeLine({0, y, z}, 0, n, row);
}

}  // namespace

void saveVolume(const Volume& volume, const std::string& path) {
  FilePtr f(std::fopen(path.c_str(), "wb"));
  if (!f)
    throw VolumeFileError(path, std::string("cannot open for writing: ") + std::strerror(errno));
  std::string header = volumeFileHeader(volume) + "\n";
  bool ok = std::fwrite(header.data(), 1, header.size(), f.get()) == header.size();
  // Row by row, so a sparse sky is never made dense in memory.
  const glm::ivec3 d = volume.dims();
  std::vector<float> row(size_t(d.x));
  for (int z = 0; z < d.z && ok; ++z)
    for (int y = 0; y < d.y && ok; ++y) {
      volume.readLine({0, y, z}, 0, d.x, row.data());
      ok = std::fwrite(row.data(), sizeof(float), row.size(), f.get()) == row.size();
    }
  if (!ok || std::fflush(f.get()) != 0)
    throw VolumeFileError(path, std::string("write failed: ") + std::strerror(errno));
}

Volume readVolume(std::istream& in, const std::string& name, std::optional<uint64_t> size) {
  std::string line;
  for (int c; (c = in.get()) != '\n';) {
    if (c == std::char_traits<char>::eof())
      throw VolumeFileError(name, "no header line (file empty or not a cloudbrush volume)");
    if (line.size() >= kMaxHeaderBytes)
      throw VolumeFileError(name, "no header line in the first " + std::to_string(kMaxHeaderBytes) +
                                      " bytes (not a cloudbrush volume)");
    line += char(c);
  }
  const VolumeFileHeader h = parseVolumeFileHeader(line, name);
  const uint64_t header_bytes = line.size() + 1;

  if (size) {
    // A file of known size: every check before the allocation, then read straight into it.
    checkVolumeFileData(h, *size >= header_bytes ? *size - header_bytes : 0, name);
    checkVolumeFileLimits(h, name);
    Volume v = allocate(h, name);
    // Row by row into the bricks: only bricks holding density take memory.
    const glm::ivec3 d = v.dims();
    std::vector<float> row(size_t(d.x));
    const std::streamsize row_bytes = std::streamsize(row.size() * sizeof(float));
    uint64_t got = 0;
    size_t first_bad = v.voxelCount();
    for (int z = 0; z < d.z; ++z)
      for (int y = 0; y < d.y; ++y) {
        in.read(reinterpret_cast<char*>(row.data()), row_bytes);
        got += uint64_t(in.gcount());
        // The file may have changed since its size was taken.
        if (in.gcount() != row_bytes) checkVolumeFileData(h, got, name);
        storeRow(v, y, z, row.data(), &first_bad);
      }
    checkVolumeFileData(h, got, name);
    if (in.peek() != std::char_traits<char>::eof())
      checkVolumeFileData(h, h.data_bytes, name, /*at_least=*/true);
    return finish(std::move(v), first_bad, name);
  }

  // Unknown size (a pipe): the limits first, then the data into a buffer that grows with what
  // arrives (at most one byte more than the header describes), then the same checks.
  checkVolumeFileLimits(h, name);
  std::vector<char> data;
  std::array<char, 16384> chunk;
  while (data.size() <= h.data_bytes) {
    in.read(chunk.data(),
            std::streamsize(std::min<uint64_t>(chunk.size(), h.data_bytes + 1 - data.size())));
    if (in.gcount() <= 0) break;
    data.insert(data.end(), chunk.data(), chunk.data() + in.gcount());
  }
  if (data.size() > h.data_bytes) checkVolumeFileData(h, h.data_bytes, name, /*at_least=*/true);
  checkVolumeFileData(h, data.size(), name);
  Volume v = allocate(h, name);
  const glm::ivec3 d = v.dims();
  std::vector<float> row(size_t(d.x));
  size_t first_bad = v.voxelCount();
  for (int z = 0; z < d.z; ++z)
    for (int y = 0; y < d.y; ++y) {
      std::memcpy(row.data(), data.data() + v.index(0, y, z) * sizeof(float),
                  row.size() * sizeof(float));
      storeRow(v, y, z, row.data(), &first_bad);
    }
  data = {};
  return finish(std::move(v), first_bad, name);
}

Volume loadVolume(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw VolumeFileError(path, "is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw VolumeFileError(path, std::string("cannot open: ") + std::strerror(errno));
  std::optional<uint64_t> size;
  if (std::filesystem::is_regular_file(path, ec)) {
    const uintmax_t bytes = std::filesystem::file_size(path, ec);
    if (!ec) size = uint64_t(bytes);
  }
  return readVolume(in, path, size);
}

}  // namespace cb
