// Bad volume files (the stored box of version 2): every size a header claims
// is checked before a voxel is allocated, and each failure is a VolumeFileError naming the file
// and the header field. The largest
// allocation made while a bad file is read is measured by replacing global operator new.
#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <new>
#include <optional>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <unistd.h>

#include "app/volume/volume_file.h"

namespace {
std::atomic<size_t> g_largest_allocation{0};
}  // namespace

// Not inlined, so the compiler sees new/delete pairs, not free() on memory from operator new.
[[gnu::noinline]] void* operator new(size_t n) {
  size_t seen = g_largest_allocation.load(std::memory_order_relaxed);
  while (n > seen && !g_largest_allocation.compare_exchange_weak(seen, n)) {
  }
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
[[gnu::noinline]] void operator delete(void* p) noexcept {
  std::free(p);
}
[[gnu::noinline]] void operator delete(void* p, size_t) noexcept {
  std::free(p);
}

namespace cb {
namespace {

const char kName[] = "vol.raw";

std::string header(const std::string& dims, const std::string& drop = "") {
  const std::string fields[][2] = {{"format", "\"cloudbrush-volume\""},
                                   {"version", "1"},
                                   {"dims", dims},
                                   {"world_min", "[-1,-1,-1]"},
                                   {"world_max", "[1,1,1]"},
                                   {"type", "\"float32\""},
                                   {"endian", "\"little\""},
                                   {"order", "\"x-fastest\""}};
  std::string h = "{";
  for (const auto& f : fields) {
    if (f[0] == drop) continue;
    if (h.size() > 1) h += ",";
    h += "\"" + f[0] + "\":" + f[1];
  }
  return h + "}\n";
}

// A version 2 header storing the box [lo, hi) of `dims`.
std::string header2(const std::string& dims, const std::string& lo, const std::string& hi) {
  return "{\"format\":\"cloudbrush-volume\",\"version\":2,\"dims\":" + dims +
         ",\"world_min\":[-1,-1,-1],\"world_max\":[1,1,1],\"stored_min\":" + lo +
         ",\"stored_max\":" + hi +
         ",\"type\":\"float32\",\"endian\":\"little\",\"order\":" + "\"x-fastest\"}\n";
}

std::string floats(size_t n) {
  return std::string(n * sizeof(float), '\0');
}

struct ReadOutcome {
  std::string error;  // empty: the read succeeded
  size_t largest_allocation = 0;
};

// Reads `bytes` as the file kName; `size` as a regular file would report it (nullopt: a pipe).
ReadOutcome read(const std::string& bytes, std::optional<uint64_t> size) {
  std::istringstream in(bytes);
  ReadOutcome r;
  g_largest_allocation = 0;
  try {
    readVolume(in, kName, size);
  } catch (const VolumeFileError& e) {
    r.largest_allocation = g_largest_allocation;
    r.error = e.what();
  }
  return r;
}

// Both ways in (regular file and pipe) fail, name the file and `field`, contain `text`, and never
// allocate more than `max_allocation` bytes.
void expectRefused(const std::string& bytes, const std::string& field, const std::string& text,
                   size_t max_allocation = 64u << 10) {
  for (std::optional<uint64_t> size :
       {std::optional<uint64_t>(bytes.size()), std::optional<uint64_t>()}) {
    SCOPED_TRACE(size ? "regular file" : "pipe");
    const ReadOutcome r = read(bytes, size);
    ASSERT_FALSE(r.error.empty()) << "accepted: " << bytes.substr(0, bytes.find('\n'));
    EXPECT_NE(r.error.find(std::string("volume file '") + kName + "'"), std::string::npos)
        << r.error;
    EXPECT_NE(r.error.find(field), std::string::npos) << r.error;
    EXPECT_NE(r.error.find(text), std::string::npos) << r.error;
    EXPECT_LE(r.largest_allocation, max_allocation) << r.error;
  }
}

TEST(VolumeFileBadInput, AGoodFileReadsBothWays) {
  const std::string bytes = header("[2,3,4]") + floats(24);
  for (std::optional<uint64_t> size :
       {std::optional<uint64_t>(bytes.size()), std::optional<uint64_t>()}) {
    std::istringstream in(bytes);
    Volume v = readVolume(in, kName, size);
    EXPECT_EQ(v.dims(), glm::ivec3(2, 3, 4));
  }
}

TEST(VolumeFileBadInput, HugeDimsAreComparedWithTheFileBeforeAllocating) {
  const ReadOutcome r = read(header("[100000,100000,100000]") + std::string(1234, '\0'),
                             header("[100000,100000,100000]").size() + 1234);
  EXPECT_EQ(r.error, std::string("volume file 'vol.raw': header field 'dims': "
                                 "100000x100000x100000 voxels need 4000000000000000 bytes of "
                                 "float32 but the file holds 1234 bytes after the header "
                                 "(truncated file or wrong dims)"));
  EXPECT_LT(r.largest_allocation, 64u << 10);
  // 2048^3 passes the per-axis limit: it used to allocate 32 GiB and abort.
  expectRefused(header("[2048,2048,2048]") + floats(4), "header field 'dims'", "2048x2048x2048");
  expectRefused(header("[1024,1024,1024]") + floats(4), "header field 'dims'", "truncated");
}

TEST(VolumeFileBadInput, NegativeZeroAndFractionalDims) {
  expectRefused(header("[4,-4,4]") + floats(64), "header field 'dims'",
                "-4 (y) is not a positive integer");
  expectRefused(header("[0,4,4]") + floats(64), "header field 'dims'",
                "0 (x) is not a positive integer");
  expectRefused(header("[4,4,4.5]") + floats(64), "header field 'dims'",
                "4.5 (z) is not a positive integer");
  expectRefused(header("[4,nan,4]") + floats(64), "header field 'dims'", "is not a positive");
  expectRefused(header("[4,4]") + floats(16), "header field 'dims'", "array of 3");
  expectRefused(header("\"4x4x4\"") + floats(64), "header field 'dims'", "array of 3");
}

TEST(VolumeFileBadInput, DimsProductOverflow) {
  expectRefused(header("[4294967296,4294967296,4294967296]") + floats(4), "header field 'dims'",
                "more bytes than a 64-bit count holds");
  // 2^62 voxels fit 64 bits, their 2^64 bytes do not.
  expectRefused(header("[4611686018427387904,1,1]") + floats(4), "header field 'dims'",
                "more bytes than a 64-bit count holds");
  expectRefused(header("[1e30,1,1]") + floats(4), "header field 'dims'",
                "does not fit a 64-bit count");
}

TEST(VolumeFileBadInput, LimitsApplyEvenWhenTheFileIsThatLarge) {
  // The file size is claimed, not written: the limits are checked before any data is read.
  const std::string axis = header("[4096,1,1]");
  std::istringstream in(axis);
  g_largest_allocation = 0;
  try {
    readVolume(in, kName, axis.size() + 4096 * 4);
    ADD_FAILURE() << "4096 voxels along x accepted";
  } catch (const VolumeFileError& e) {
    EXPECT_NE(std::string(e.what()).find("header field 'dims': 4096x1x1 exceeds 2048 voxels "
                                         "along x"),
              std::string::npos)
        << e.what();
  }
  const std::string total = header("[2048,2048,512]");
  std::istringstream in2(total);
  try {
    readVolume(in2, kName, total.size() + (uint64_t(2048) * 2048 * 512 * 4));
    ADD_FAILURE() << "2^31 voxels accepted";
  } catch (const VolumeFileError& e) {
    EXPECT_NE(std::string(e.what()).find("header field 'dims': 2048x2048x512 = 2147483648 voxels "
                                         "exceeds the limit"),
              std::string::npos)
        << e.what();
  }
  EXPECT_LT(g_largest_allocation.load(), size_t(64) << 10);
}

TEST(VolumeFileBadInput, TruncatedData) {
  expectRefused(header("[4,4,4]") + floats(63), "header field 'dims'",
                "4x4x4 voxels need 256 bytes of float32 but the file holds 252 bytes");
  expectRefused(header("[4,4,4]") + floats(63), "header field 'dims'", "truncated");
  expectRefused(header("[4,4,4]") + "\x01\x02", "header field 'dims'", "holds 2 bytes");
  expectRefused(header("[4,4,4]"), "header field 'dims'", "holds 0 bytes");
}

TEST(VolumeFileBadInput, TrailingBytes) {
  const std::string bytes = header("[4,4,4]") + floats(64) + "xyz";
  const ReadOutcome file = read(bytes, bytes.size());
  EXPECT_NE(file.error.find("header field 'dims': 4x4x4 voxels need 256 bytes of float32 but the "
                            "file holds 259 bytes after the header (trailing data"),
            std::string::npos)
      << file.error;
  const ReadOutcome pipe = read(bytes, std::nullopt);
  EXPECT_NE(pipe.error.find("holds more than 256 bytes after the header (trailing data"),
            std::string::npos)
      << pipe.error;
}

TEST(VolumeFileBadInput, NonJsonHeader) {
  expectRefused(std::string("P6\n4 4\n255\n") + std::string(48, '\0'), "header line",
                "malformed JSON at byte 0: expected '{'");
  expectRefused("{\"format\":\"cloudbrush-volume\",\n", "header line", "malformed JSON");
  expectRefused("{\"format\":\"cloudbrush-volume\"} trailing\n", "header line",
                "unexpected text after the header object");
  expectRefused(std::string(5000, 'x'), "no header line", "first 4096 bytes");
  expectRefused("", "no header line", "file empty");
}

TEST(VolumeFileBadInput, MissingFieldIsNamed) {
  for (const char* field :
       {"format", "version", "dims", "world_min", "world_max", "type", "endian", "order"}) {
    SCOPED_TRACE(field);
    expectRefused(header("[4,4,4]", field) + floats(64),
                  std::string("header field '") + field + "' is missing", "");
  }
}

TEST(VolumeFileBadInput, OtherFieldsAreNamed) {
  std::string h = header("[4,4,4]");
  auto with = [&](const std::string& from, const std::string& to) {
    std::string r = h;
    r.replace(r.find(from), from.size(), to);
    return r + floats(64);
  };
  expectRefused(with("\"version\":1", "\"version\":3"), "header field 'version'",
                "3 is unsupported (this build reads versions 1 and 2)");
  expectRefused(with("\"version\":1", "\"version\":\"2\""), "header field 'version'",
                "\"2\" is unsupported");
  expectRefused(with("\"float32\"", "\"float16\""), "header field 'type'", "\"float16\"");
  expectRefused(with("\"little\"", "\"big\""), "header field 'endian'", "\"big\"");
  expectRefused(with("\"world_min\":[-1,-1,-1]", "\"world_min\":[-1,-1]"),
                "header field 'world_min'", "array of 3 numbers");
  expectRefused(with("\"world_max\":[1,1,1]", "\"world_max\":[1,1e39,1]"),
                "header field 'world_max'", "not a finite float");
  expectRefused(with("\"world_max\":[1,1,1]", "\"world_max\":[1,-1,1]"), "header field 'world_max'",
                "must be above world_min");
}

TEST(VolumeFileBadInput, AVersionTwoFileAllocatesForItsStoredBytesOnly) {
  // The largest virtual extent the limits allow (2^30 voxels, 4 GiB dense) with one stored
  // voxel: the brick table and one brick are allocated, never the grid.
  const std::string bytes =
      header2("[2048,2048,256]", "[5,6,7]", "[6,7,8]") + std::string("\0\0\x80\x3f", 4);
  for (std::optional<uint64_t> size :
       {std::optional<uint64_t>(bytes.size()), std::optional<uint64_t>()}) {
    SCOPED_TRACE(size ? "regular file" : "pipe");
    std::istringstream in(bytes);
    g_largest_allocation = 0;
    const Volume v = readVolume(in, kName, size);
    EXPECT_LE(g_largest_allocation.load(), size_t(4) << 20);
    EXPECT_EQ(v.dims(), glm::ivec3(2048, 2048, 256));
    EXPECT_EQ(v.allocatedBricks(), 1u);
    EXPECT_EQ(v.at(5, 6, 7), 1.0f);
    EXPECT_EQ(v.at(5, 6, 8), 0.0f);
  }
  // The virtual extent still obeys the limits, stored bytes or not.
  expectRefused(header2("[2048,2048,512]", "[0,0,0]", "[0,0,0]"), "header field 'dims'",
                "2048x2048x512 = 2147483648 voxels exceeds the limit");
  expectRefused(header2("[4096,1,1]", "[0,0,0]", "[1,1,1]") + floats(1), "header field 'dims'",
                "4096x1x1 exceeds 2048 voxels along x");
}

TEST(VolumeFileBadInput, AStoredBoxIsComparedWithTheFileBeforeAllocating) {
  expectRefused(header2("[1024,1024,1024]", "[0,0,0]", "[1024,1024,1024]") + floats(4),
                "header fields 'stored_min', 'stored_max'",
                "the stored box [0,0,0]..[1024,1024,1024] (1073741824 voxels) needs 4294967296 "
                "bytes of float32 but the file holds 16 bytes after the header (truncated file "
                "or wrong box)");
  const std::string trailing = header2("[4,4,4]", "[0,0,0]", "[2,2,2]") + floats(9);
  expectRefused(trailing, "stored_max'", "(trailing data or wrong box)");
  EXPECT_NE(
      read(trailing, trailing.size())
          .error.find("needs 32 bytes of float32 but the file holds 36 bytes after the header"),
      std::string::npos);
  expectRefused(header2("[4,4,4]", "[0,0,0]", "[0,0,0]") + floats(1), "stored_max'",
                "[0,0,0]..[0,0,0] (0 voxels) needs 0 bytes");
}

TEST(VolumeFileBadInput, StoredBoxFieldsAreNamed) {
  const std::string body = floats(8);
  expectRefused(header2("[4,4,4]", "[0,0,0]", "[2,2,5]") + body, "header field 'stored_max'",
                "5 (z) lies outside dims 4x4x4");
  expectRefused(header2("[4,4,4]", "[5,0,0]", "[5,2,2]") + body, "header field 'stored_min'",
                "5 (x) lies outside dims 4x4x4");
  expectRefused(header2("[4,4,4]", "[0,-1,0]", "[2,2,2]") + body, "header field 'stored_min'",
                "-1 (y) is not a non-negative integer");
  expectRefused(header2("[4,4,4]", "[0,0,0]", "[2,2,1.5]") + body, "header field 'stored_max'",
                "1.5 (z) is not a non-negative integer");
  expectRefused(header2("[4,4,4]", "[0,0,0]", "[2,nan,2]") + body, "header field 'stored_max'",
                "is not a non-negative integer");
  expectRefused(header2("[4,4,4]", "[0,0,0]", "[1e300,2,2]") + body, "header field 'stored_max'",
                "1e+300 (x) lies outside dims");
  expectRefused(header2("[4,4,4]", "[3,0,0]", "[2,2,2]") + body, "header field 'stored_max'",
                "2 (x) is below stored_min 3");
  expectRefused(header2("[4,4,4]", "[0,0]", "[2,2,2]") + body, "header field 'stored_min'",
                "must be an array of 3 non-negative integers");
  expectRefused(header2("[4,4,4]", "\"0,0,0\"", "[2,2,2]") + body, "header field 'stored_min'",
                "must be an array of 3");
  std::string no_max = header2("[4,4,4]", "[0,0,0]", "[2,2,2]");
  no_max.replace(no_max.find("\"stored_max\""), 12, "\"stored_mux\"");
  expectRefused(no_max + body, "header field 'stored_max' is missing", "");
  // Version 1 stores the whole grid: a stored box there is a mistake, not ignored.
  std::string v1 = header2("[2,2,2]", "[0,0,0]", "[2,2,2]");
  v1.replace(v1.find("\"version\":2"), 11, "\"version\":1");
  expectRefused(v1 + body, "header field 'stored_min'", "is not part of version 1");
}

TEST(VolumeFileBadInput, LoadVolumeUsesTheFileSize) {
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("cb_volume_bad_input_" + std::to_string(::getpid()) + "_huge.cbvol"))
                               .string();
  std::ofstream(path, std::ios::binary) << header("[2048,2048,2048]") << std::string(1234, '\0');
  g_largest_allocation = 0;
  try {
    loadVolume(path);
    ADD_FAILURE() << "accepted";
  } catch (const VolumeFileError& e) {
    EXPECT_NE(std::string(e.what()).find("volume file '" + path +
                                         "': header field 'dims': "
                                         "2048x2048x2048 voxels need 34359738368 bytes"),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("holds 1234 bytes"), std::string::npos) << e.what();
  }
  EXPECT_LT(g_largest_allocation.load(), size_t(64) << 10);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace cb
