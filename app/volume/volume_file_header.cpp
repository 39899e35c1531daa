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

}  // namespace

std::string formatDims(const VolumeFileHeader& header) {
  return std::to_string(header.dims[0]) + "x" + std::to_string(header.dims[1]) + "x" +
         std::to_string(header.dims[2]);
}

std::string volumeFileHeader(const Volume& volume) {
  glm::ivec3 d = volume.dims();
  std::ostringstream s;
  s << "{\"format\":\"cloudbrush-volume\",\"version\":" << kVolumeFileVersion << ",\"dims\":["
    << d.x << "," << d.y << "," << d.z << "],\"world_min\":" << formatVec(volume.worldMin())
    << ",\"world_max\":" << formatVec(volume.worldMax())
    << ",\"type\":\"float32\",\"endian\":\"little\",\"order\":\"x-fastest\"}";
  return s.str();
}

VolumeFileHeader parseVolumeFileHeader(const std::string& line, const std::string& name) {
  const Header h = HeaderParser(line, name).parse();
  expectString(h, "format", "cloudbrush-volume", name);
  const HeaderValue& version = field(h, "version", name);
  if (version.is_string || version.is_array || version.numbers[0] != double(kVolumeFileVersion))
    fieldError(
        name, "version",
        ": unsupported (this build reads version " + std::to_string(kVolumeFileVersion) + ")");
  expectString(h, "type", "float32", name);
  expectString(h, "endian", "little", name);
  expectString(h, "order", "x-fastest", name);

  VolumeFileHeader out;
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
  if (__builtin_mul_overflow(out.dims[0], out.dims[1], &out.voxel_count) ||
      __builtin_mul_overflow(out.voxel_count, out.dims[2], &out.voxel_count) ||
      __builtin_mul_overflow(out.voxel_count, sizeof(float), &out.data_bytes))
    fieldError(
        name, "dims",
        ": " + formatDims(out) + " voxels of float32 need more bytes than a 64-bit count holds");

  out.world_min = vecField(h, "world_min", name);
  out.world_max = vecField(h, "world_max", name);
  if (!glm::all(glm::lessThan(out.world_min, out.world_max)))
    fieldError(name, "world_max",
               ": " + formatVec(out.world_max) + " must be above world_min " +
                   formatVec(out.world_min) + " on every axis");
  return out;
}

void checkVolumeFileData(const VolumeFileHeader& header, uint64_t bytes_after_header,
                         const std::string& name, bool at_least) {
  if (bytes_after_header == header.data_bytes && !at_least) return;
  const bool short_data = bytes_after_header < header.data_bytes;
  fieldError(name, "dims",
             ": " + formatDims(header) + " voxels need " + std::to_string(header.data_bytes) +
                 " bytes of float32 but the file holds " + (at_least ? "more than " : "") +
                 std::to_string(bytes_after_header) + " bytes after the header (" +
                 (short_data ? "truncated file or wrong dims)" : "trailing data or wrong dims)"));
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
