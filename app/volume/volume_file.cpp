#include "app/volume/volume_file.h"

#include <bit>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <sstream>
#include <vector>

namespace cb {
namespace {

static_assert(std::endian::native == std::endian::little,
              "volume files are little-endian; add byte swapping for this platform");

constexpr size_t kMaxHeaderBytes = 4096;

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw VolumeFileError("volume file '" + path + "': " + what);
}

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;

// A header value: a string, a number or an array of numbers (all the header needs).
struct HeaderValue {
  std::string text;
  std::vector<double> numbers;
  bool is_string = false;
};

// Parses the flat JSON object of the header line.
class HeaderParser {
 public:
  HeaderParser(const std::string& text, const std::string& path) : s_(text), path_(path) {}

  std::map<std::string, HeaderValue> parse() {
    std::map<std::string, HeaderValue> out;
    expect('{');
    skipSpace();
    if (peek() == '}') return out;
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
      skipSpace();
      if (i_ != s_.size()) error("unexpected text after the header object");
      return out;
    }
  }

 private:
  [[noreturn]] void error(const std::string& what) {
    fail(path_, "malformed JSON header at byte " + std::to_string(i_) + ": " + what);
  }
  void skipSpace() {
    while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_]))) ++i_;
  }
  char peek() { return i_ < s_.size() ? s_[i_] : '\0'; }
  void expect(char c) {
    skipSpace();
    if (peek() != c) error(std::string("expected '") + c + "'");
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
  const std::string& path_;
  size_t i_ = 0;
};

std::string formatVec(glm::vec3 v) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "[%.9g,%.9g,%.9g]", double(v.x), double(v.y), double(v.z));
  return buf;
}

const HeaderValue& field(const std::map<std::string, HeaderValue>& h, const std::string& key,
                         const std::string& path) {
  auto it = h.find(key);
  if (it == h.end()) fail(path, "header has no \"" + key + "\" field");
  return it->second;
}

std::string stringField(const std::map<std::string, HeaderValue>& h, const std::string& key,
                        const std::string& path) {
  const HeaderValue& v = field(h, key, path);
  if (!v.is_string) fail(path, "header field \"" + key + "\" must be a string");
  return v.text;
}

glm::vec3 vecField(const std::map<std::string, HeaderValue>& h, const std::string& key,
                   const std::string& path) {
  const HeaderValue& v = field(h, key, path);
  if (v.is_string || v.numbers.size() != 3)
    fail(path, "header field \"" + key + "\" must be an array of 3 numbers");
  for (double d : v.numbers)
    if (!std::isfinite(d)) fail(path, "header field \"" + key + "\" has a non-finite number");
  return glm::vec3(float(v.numbers[0]), float(v.numbers[1]), float(v.numbers[2]));
}

}  // namespace

std::string volumeFileHeader(const Volume& volume) {
  glm::ivec3 d = volume.dims();
  std::ostringstream s;
  s << "{\"format\":\"cloudbrush-volume\",\"version\":" << kVolumeFileVersion << ",\"dims\":["
    << d.x << "," << d.y << "," << d.z << "],\"world_min\":" << formatVec(volume.worldMin())
    << ",\"world_max\":" << formatVec(volume.worldMax())
    << ",\"type\":\"float32\",\"endian\":\"little\",\"order\":\"x-fastest\"}";
  return s.str();
}

void saveVolume(const Volume& volume, const std::string& path) {
  FilePtr f(std::fopen(path.c_str(), "wb"));
  if (!f) fail(path, std::string("cannot open for writing: ") + std::strerror(errno));
  std::string header = volumeFileHeader(volume) + "\n";
  bool ok = std::fwrite(header.data(), 1, header.size(), f.get()) == header.size() &&
            std::fwrite(volume.data(), sizeof(float), volume.voxelCount(), f.get()) ==
                volume.voxelCount();
  if (!ok || std::fflush(f.get()) != 0)
    fail(path, std::string("write failed: ") + std::strerror(errno));
}

Volume loadVolume(const std::string& path) {
  FilePtr f(std::fopen(path.c_str(), "rb"));
  if (!f) fail(path, std::string("cannot open: ") + std::strerror(errno));
  std::string header;
  for (int c; (c = std::fgetc(f.get())) != '\n';) {
    if (c == EOF) fail(path, "no header line (file empty or not a cloudbrush volume)");
    if (header.size() >= kMaxHeaderBytes)
      fail(path, "no header line in the first 4096 bytes (not a cloudbrush volume)");
    header += char(c);
  }
  auto h = HeaderParser(header, path).parse();
  if (stringField(h, "format", path) != "cloudbrush-volume")
    fail(path,
         "format is \"" + stringField(h, "format", path) + "\", expected \"cloudbrush-volume\"");
  const HeaderValue& version = field(h, "version", path);
  if (version.is_string || version.numbers.size() != 1 ||
      version.numbers[0] != double(kVolumeFileVersion))
    fail(path, "unsupported version (this build reads version " +
                   std::to_string(kVolumeFileVersion) + ")");
  if (stringField(h, "type", path) != "float32")
    fail(path, "type \"" + stringField(h, "type", path) + "\" is not supported (float32 only)");
  if (stringField(h, "endian", path) != "little")
    fail(path, "endian \"" + stringField(h, "endian", path) + "\" is not supported");
  if (stringField(h, "order", path) != "x-fastest")
    fail(path, "order \"" + stringField(h, "order", path) + "\" is not supported");
  const HeaderValue& dims_value = field(h, "dims", path);
  if (dims_value.is_string || dims_value.numbers.size() != 3)
    fail(path, "header field \"dims\" must be an array of 3 integers");
  glm::ivec3 dims;
  for (int i = 0; i < 3; ++i) {
    double d = dims_value.numbers[size_t(i)];
    if (d != std::floor(d) || d < 1 || d > 2048)
      fail(path, "dims must be integers in 1..2048, got " + std::to_string(d));
    dims[i] = int(d);
  }
  glm::vec3 wmin = vecField(h, "world_min", path), wmax = vecField(h, "world_max", path);
  if (!glm::all(glm::lessThan(wmin, wmax)))
    fail(path, "world_min " + formatVec(wmin) + " must be below world_max " + formatVec(wmax));

  Volume v(dims, wmin, wmax);
  size_t n = v.voxelCount();
  size_t got = std::fread(v.data(), sizeof(float), n, f.get());
  if (got != n)
    fail(path, "truncated: header says " + std::to_string(dims.x) + "x" + std::to_string(dims.y) +
                   "x" + std::to_string(dims.z) + " = " + std::to_string(n * 4) +
                   " bytes of float32 data, found " + std::to_string(got * 4) + " whole bytes");
  if (std::fgetc(f.get()) != EOF)
    fail(path, "trailing data after the " + std::to_string(n * 4) +
                   " bytes the header describes (dims mismatch?)");
  const float* d = v.data();
  for (size_t i = 0; i < n; ++i)
    if (!std::isfinite(d[i])) fail(path, "non-finite density at voxel index " + std::to_string(i));
  v.markDirty(v.bounds());
  return v;
}

}  // namespace cb
