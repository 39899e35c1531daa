#include "app/volume/volume_file_header.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <sstream>
#include <vector>

namespace cb {
namespace {

// A header value: a string, a number or an array of numbers (all the header needs).
struct HeaderValue {
  std::string text;
  std::vector<double> numbers;
  bool is_string = false;
  bool is_array = false;
};
using Header = std::map<std::string, HeaderValue>;

// Parses the flat JSON object of the header line.
class HeaderParser {
 public:
  HeaderParser(const std::string& text, const std::string& name) : s_(text), name_(name) {}

  Header parse() {
    Header out;
    expect('{');
    skipSpace();
    if (peek() == '}') {
      ++i_;
      end();
      return out;
    }
    for (;;) {
      std::string key = parseString();
      expect(':');
      out[key] = parseValue();
      skipSpace();
      if (peek() == ',') {
        ++i_;
        continue;
      }
      expect('}');
      end();
      return out;
    }
  }

 private:
  [[noreturn]] void error(const std::string& what) {
    throw VolumeFileError(
        name_, "header line: malformed JSON at byte " + std::to_string(i_) + ": " + what);
  }
  void end() {
    skipSpace();
    if (i_ != s_.size()) error("unexpected text after the header object");
  }
  void skipSpace() {
    while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_]))) ++i_;
  }
  char peek() { return i_ < s_.size() ? s_[i_] : '\0'; }
  void expect(char c) {
    skipSpace();
    if (i_ >= s_.size() || s_[i_] != c) error(std::string("expected '") + c + "'");
    ++i_;
  }
  std::string parseString() {
    expect('"');
    std::string r;
    while (i_ < s_.size() && s_[i_] != '"') {
      if (s_[i_] == '\\') error("escapes are not supported in header strings");
      r += s_[i_++];
    }
    if (i_ >= s_.size()) error("unterminated string");
    ++i_;
    return r;
  }
  double parseNumber() {
    skipSpace();
    const char* begin = s_.c_str() + i_;
    char* end = nullptr;
    double v = std::strtod(begin, &end);
    if (end == begin) error("expected a number");
    i_ += size_t(end - begin);
    return v;
  }
  HeaderValue parseValue() {
    skipSpace();
    HeaderValue v;
    if (peek() == '"') {
      v.text = parseString();
      v.is_string = true;
    } else if (peek() == '[') {
      v.is_array = true;
      ++i_;
      skipSpace();
      if (peek() != ']') {
        for (;;) {
          v.numbers.push_back(parseNumber());
          skipSpace();
          if (peek() == ',') {
            ++i_;
            continue;
          }
          break;
        }
      }
      expect(']');
    } else {
      v.numbers.push_back(parseNumber());
    }
    return v;
  }

  const std::string& s_;
  const std::string& name_;
  size_t i_ = 0;
};

std::string formatNumber(double d) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.15g", d);
  return buf;
}

std::string formatVec(glm::vec3 v) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "[%.9g,%.9g,%.9g]", double(v.x), double(v.y), double(v.z));
  return buf;
}

[[noreturn]] void fieldError(const std::string& name, const std::string& key,
                             const std::string& problem) {
  throw VolumeFileError(name, "header field '" + key + "'" + problem);
}

const HeaderValue& field(const Header& h, const std::string& key, const std::string& name) {
  auto it = h.find(key);
  if (it == h.end()) fieldError(name, key, " is missing");
  return it->second;
}

std::string stringField(const Header& h, const std::string& key, const std::string& name) {
  const HeaderValue& v = field(h, key, name);
  if (!v.is_string) fieldError(name, key, " must be a string");
  return v.text;
}

void expectString(const Header& h, const std::string& key, const std::string& expected,
                  const std::string& name) {
  const std::string value = stringField(h, key, name);
  if (value != expected)
    fieldError(name, key, ": \"" + value + "\" is not supported (expected \"" + expected + "\")");
}

glm::vec3 vecField(const Header& h, const std::string& key, const std::string& name) {
  const HeaderValue& v = field(h, key, name);
  if (!v.is_array || v.numbers.size() != 3) fieldError(name, key, " must be an array of 3 numbers");
  for (double d : v.numbers)
    if (!std::isfinite(d) || !std::isfinite(float(d)))
      fieldError(name, key, ": " + formatNumber(d) + " is not a finite float");
  return glm::vec3(float(v.numbers[0]), float(v.numbers[1]), float(v.numbers[2]));
}

// A corner of the stored box: 3 non-negative integers, each at most the dims along its axis.
void storedCorner(const Header& h, const std::string& key, const uint64_t (&dims)[3],
                  uint64_t (&out)[3], const std::string& name) {
  const HeaderValue& v = field(h, key, name);
  if (!v.is_array || v.numbers.size() != 3)
    fieldError(name, key, " must be an array of 3 non-negative integers");
  for (size_t i = 0; i < 3; ++i) {
    const double d = v.numbers[i];
    if (!(d >= 0) || d != std::floor(d))  // also NaN
      fieldError(name, key,
                 ": " + formatNumber(d) + " (" + "xyz"[i] + ") is not a non-negative integer");
    if (d > double(dims[i]))
      fieldError(name, key,
                 ": " + formatNumber(d) + " (" + "xyz"[i] + ") lies outside dims " +
                     std::to_string(dims[0]) + "x" + std::to_string(dims[1]) + "x" +
                     std::to_string(dims[2]));
    out[i] = uint64_t(d);
  }
}

}  // namespace

std::string formatDims(const VolumeFileHeader& header) {
  return std::to_string(header.dims[0]) + "x" + std::to_string(header.dims[1]) + "x" +
         std::to_string(header.dims[2]);
}

std::string volumeFileHeader(const Volume& volume, const VoxelBox& stored) {
  const glm::ivec3 d = volume.dims();
  const VoxelBox box = stored.intersect(volume.bounds());  // an empty box becomes [0,0,0]..[0,0,0]
  std::ostringstream s;
  s << "{\"format\":\"cloudbrush-volume\",\"version\":" << kVolumeFileVersion << ",\"dims\":["
    << d.x << "," << d.y << "," << d.z << "],\"world_min\":" << formatVec(volume.worldMin())
    << ",\"world_max\":" << formatVec(volume.worldMax()) << ",\"stored_min\":[" << box.lo.x << ","
    << box.lo.y << "," << box.lo.z << "],\"stored_max\":[" << box.hi.x << "," << box.hi.y << ","
    << box.hi.z << "],\"type\":\"float32\",\"endian\":\"little\",\"order\":\"x-fastest\"}";
  return s.str();
}

VolumeFileHeader parseVolumeFileHeader(const std::string& line, const std::string& name) {
  const Header h = HeaderParser(line, name).parse();
  expectString(h, "format", "cloudbrush-volume", name);
  const HeaderValue& version = field(h, "version", name);
  if (version.is_string || version.is_array || (version.numbers[0] != 1 && version.numbers[0] != 2))
    fieldError(name, "version",
               ": " +
                   (version.is_string  ? "\"" + version.text + "\""
                    : version.is_array ? std::string("an array")
                                       : formatNumber(version.numbers[0])) +
                   " is unsupported (this build reads versions 1 and 2)");
  expectString(h, "type", "float32", name);
  expectString(h, "endian", "little", name);
  expectString(h, "order", "x-fastest", name);

  VolumeFileHeader out;
  out.version = int(version.numbers[0]);
  const HeaderValue& dims = field(h, "dims", name);
  if (!dims.is_array || dims.numbers.size() != 3)
    fieldError(name, "dims", " must be an array of 3 positive integers");
  for (size_t i = 0; i < 3; ++i) {
    const double d = dims.numbers[i];
    if (!(d >= 1) || d != std::floor(d))  // also NaN
      fieldError(name, "dims",
                 ": " + formatNumber(d) + " (" + "xyz"[i] + ") is not a positive integer");
    if (d >= 18446744073709551616.0)  // 2^64
      fieldError(name, "dims",
                 ": " + formatNumber(d) + " (" + "xyz"[i] + ") does not fit a 64-bit count");
    out.dims[i] = uint64_t(d);
  }
  uint64_t dense_bytes = 0;
  if (__builtin_mul_overflow(out.dims[0], out.dims[1], &out.voxel_count) ||
      __builtin_mul_overflow(out.voxel_count, out.dims[2], &out.voxel_count) ||
      __builtin_mul_overflow(out.voxel_count, sizeof(float), &dense_bytes))
    fieldError(
        name, "dims",
        ": " + formatDims(out) + " voxels of float32 need more bytes than a 64-bit count holds");

  out.world_min = vecField(h, "world_min", name);
  out.world_max = vecField(h, "world_max", name);
  if (!glm::all(glm::lessThan(out.world_min, out.world_max)))
    fieldError(name, "world_max",
               ": " + formatVec(out.world_max) + " must be above world_min " +
                   formatVec(out.world_min) + " on every axis");

  if (out.version == 1) {
    // The whole grid, x fastest.
    for (const char* key : {"stored_min", "stored_max"})
      if (h.count(key))
        fieldError(name, key, " is not part of version 1 (which stores the whole grid)");
    for (size_t i = 0; i < 3; ++i) out.stored_max[i] = out.dims[i];
  } else {
    storedCorner(h, "stored_min", out.dims, out.stored_min, name);
    storedCorner(h, "stored_max", out.dims, out.stored_max, name);
    for (size_t i = 0; i < 3; ++i)
      if (out.stored_max[i] < out.stored_min[i])
        fieldError(name, "stored_max",
                   ": " + std::to_string(out.stored_max[i]) + " (" + "xyz"[i] +
                       ") is below stored_min " + std::to_string(out.stored_min[i]));
  }
  // At most voxel_count, whose bytes fit 64 bits (checked above).
  out.stored_voxels = 1;
  for (size_t i = 0; i < 3; ++i) out.stored_voxels *= out.stored_max[i] - out.stored_min[i];
  out.data_bytes = out.stored_voxels * sizeof(float);
  return out;
}

std::string formatStoredBox(const VolumeFileHeader& header) {
  auto corner = [](const uint64_t* c) {
    return "[" + std::to_string(c[0]) + "," + std::to_string(c[1]) + "," + std::to_string(c[2]) +
           "]";
  };
  return corner(header.stored_min) + ".." + corner(header.stored_max);
}

void checkVolumeFileData(const VolumeFileHeader& header, uint64_t bytes_after_header,
                         const std::string& name, bool at_least) {
  if (bytes_after_header == header.data_bytes && !at_least) return;
  const bool short_data = bytes_after_header < header.data_bytes;
  const std::string holds = " bytes of float32 but the file holds " +
                            std::string(at_least ? "more than " : "") +
                            std::to_string(bytes_after_header) + " bytes after the header (" +
                            (short_data ? "truncated file or " : "trailing data or ");
  if (header.version == 1)
    fieldError(name, "dims",
               ": " + formatDims(header) + " voxels need " + std::to_string(header.data_bytes) +
                   holds + "wrong dims)");
  throw VolumeFileError(name, "header fields 'stored_min', 'stored_max': the stored box " +
                                  formatStoredBox(header) + " (" +
                                  std::to_string(header.stored_voxels) + " voxels) needs " +
                                  std::to_string(header.data_bytes) + holds + "wrong box)");
}

void checkVolumeFileLimits(const VolumeFileHeader& header, const std::string& name) {
  for (size_t i = 0; i < 3; ++i)
    if (header.dims[i] > uint64_t(kMaxVolumeDim))
      fieldError(name, "dims",
                 ": " + formatDims(header) + " exceeds " + std::to_string(kMaxVolumeDim) +
                     " voxels along " + "xyz"[i]);
  if (header.voxel_count > kMaxVolumeFileVoxels)
    fieldError(name, "dims",
               ": " + formatDims(header) + " = " + std::to_string(header.voxel_count) +
                   " voxels exceeds the limit of " + std::to_string(kMaxVolumeFileVoxels) +
                   " (1024^3, 4 GiB of float32)");
}

}  // namespace cb
