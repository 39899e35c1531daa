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

#include "app/core/atomic_file.h"

namespace cb {
namespace {

static_assert(std::endian::native == std::endian::little,
              "volume files are little-endian; add byte swapping for this platform");

constexpr size_t kMaxHeaderBytes = 4096;

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;

// The volume the header describes, still zero; its brick table (sized by the header's dims,
// which the limits bound) is the only allocation the header sizes, made after every check.
Volume allocate(const VolumeFileHeader& h, const std::string& name) {
  try {
    return Volume(glm::ivec3(int(h.dims[0]), int(h.dims[1]), int(h.dims[2])), h.world_min,
                  h.world_max);
  } catch (const std::bad_alloc&) {
    throw VolumeFileError(name, "header field 'dims': the brick table of " + formatDims(h) +
                                    " voxels does not fit in memory");
  }
}

// Fills `v` with the stored box's rows (x fastest, then y, then z), each taken from
// `next_row(float* row, size_t n)`, which throws when the data ends early. Only the stored box
// is walked and writeLine allocates bricks only for non-zero runs, so memory and time follow
// the bytes stored, not the virtual extent. Refuses a non-finite density; marks the whole
// volume changed.
template <typename NextRow>
Volume fillStoredBox(Volume v, const VolumeFileHeader& h, const std::string& name,
                     NextRow&& next_row) {
  const glm::ivec3 lo(int(h.stored_min[0]), int(h.stored_min[1]), int(h.stored_min[2]));
  const glm::ivec3 hi(int(h.stored_max[0]), int(h.stored_max[1]), int(h.stored_max[2]));
  const int width = hi.x - lo.x;
  std::vector<float> row(size_t(std::max(width, 0)));
  if (h.stored_voxels > 0)
    for (int z = lo.z; z < hi.z; ++z)
      for (int y = lo.y; y < hi.y; ++y) {
        next_row(row.data(), row.size());
        for (int x = 0; x < width; ++x)
          if (!std::isfinite(row[size_t(x)]))
            throw VolumeFileError(name, "non-finite density at voxel index " +
                                            std::to_string(v.index(lo.x + x, y, z)) + " (x " +
                                            std::to_string(lo.x + x) + ", y " + std::to_string(y) +
                                            ", z " + std::to_string(z) + ")");
        v.writeLine({lo.x, y, z}, 0, width, row.data());
      }
  v.markDirty(v.bounds());
  return v;
}

// The smallest box holding every voxel whose bit pattern is not zero (every voxel outside it
// reads back as +0, so -0 is kept too). Looks into the allocated bricks only, skipping those
// already inside the box found so far; empty when no voxel is non-zero.
VoxelBox nonZeroBox(const Volume& volume) {
  VoxelBox box;
  for (const glm::ivec3 b : volume.allocatedBrickList()) {
    const VoxelBox bb = volume.brickBox(b);
    if (!box.empty() && box.unite(bb) == box) continue;
    const float* voxels = volume.brick(b);
    const glm::ivec3 o = b * Volume::kBrickSize;
    for (int z = bb.lo.z; z < bb.hi.z; ++z)
      for (int y = bb.lo.y; y < bb.hi.y; ++y) {
        const float* row =
            voxels + (size_t(z - o.z) * Volume::kBrickSize + size_t(y - o.y)) * Volume::kBrickSize;
        int first = -1, last = -1;
        for (int x = bb.lo.x; x < bb.hi.x; ++x)
          if (std::bit_cast<uint32_t>(row[x - o.x]) != 0) {
            if (first < 0) first = x;
            last = x;
          }
        if (first >= 0) box = box.unite({{first, y, z}, {last + 1, y + 1, z + 1}});
      }
  }
  return box;
}

}  // namespace

void saveVolume(const Volume& volume, const std::string& path) {
  // Written beside `path` and renamed over it once on the disk (app/core/atomic_file.h): a full
  // disk or a power cut never leaves a torn volume under the final name.
  AtomicFileReplacement out(path);
  {
    FilePtr f(std::fopen(out.tempPath().c_str(), "wb"));
    if (!f)
      throw VolumeFileError(path, std::string("cannot open for writing: ") + std::strerror(errno));
    const VoxelBox stored = nonZeroBox(volume);
    std::string header = volumeFileHeader(volume, stored) + "\n";
    bool ok = std::fwrite(header.data(), 1, header.size(), f.get()) == header.size();
    // The stored box row by row, so a sparse sky is never made dense in memory nor walked whole.
    std::vector<float> row(size_t(stored.hi.x - stored.lo.x));
    if (!stored.empty())
      for (int z = stored.lo.z; z < stored.hi.z && ok; ++z)
        for (int y = stored.lo.y; y < stored.hi.y && ok; ++y) {
          volume.readLine({stored.lo.x, y, z}, 0, int(row.size()), row.data());
          ok = std::fwrite(row.data(), sizeof(float), row.size(), f.get()) == row.size();
        }
    if (!ok || std::fflush(f.get()) != 0 || std::fclose(f.release()) != 0)
      throw VolumeFileError(path, std::string("write failed: ") + std::strerror(errno));
  }
  std::string error;
  if (!out.commit(&error)) throw VolumeFileError(path, error);
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
    // A file of known size: every check before the allocation, then read row by row.
    checkVolumeFileData(h, *size >= header_bytes ? *size - header_bytes : 0, name);
    checkVolumeFileLimits(h, name);
    uint64_t got = 0;
    Volume v = fillStoredBox(allocate(h, name), h, name, [&](float* row, size_t n) {
      const std::streamsize row_bytes = std::streamsize(n * sizeof(float));
      in.read(reinterpret_cast<char*>(row), row_bytes);
      got += uint64_t(in.gcount());
      // The file may have changed since its size was taken.
      if (in.gcount() != row_bytes) checkVolumeFileData(h, got, name);
    });
    checkVolumeFileData(h, got, name);
    if (in.peek() != std::char_traits<char>::eof())
      checkVolumeFileData(h, h.data_bytes, name, /*at_least=*/true);
    return v;
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
  size_t offset = 0;
  return fillStoredBox(allocate(h, name), h, name, [&](float* row, size_t n) {
    std::memcpy(row, data.data() + offset, n * sizeof(float));
    offset += n * sizeof(float);
  });
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
