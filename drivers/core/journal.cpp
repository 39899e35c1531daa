#include "drivers/core/journal.h"

#include <array>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <fcntl.h>
#include <unistd.h>

namespace cb {
namespace {

constexpr char kMagic[8] = {'C', 'B', 'J', 'O', 'U', 'R', 'N', 'L'};
constexpr size_t kHeaderSize = 16;
constexpr size_t kRecordHead = 16;  // type, length, t_ns
constexpr uint32_t kMaxPayload = 64u << 20;

int64_t monotonicNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

// The directory entry of a new file reaches the disk only when its directory is synced.
void syncParentDirectory(const std::string& path) {
  std::string dir = std::filesystem::path(path).parent_path().string();
  if (dir.empty()) dir = ".";
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

class ByteWriter {
 public:
  template <typename T>
  void put(T v) {
    static_assert(std::is_trivially_copyable_v<T>);
    uint8_t b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));  // x86-64 and aarch64 are little-endian; see header
    bytes.insert(bytes.end(), b, b + sizeof(T));
  }
  std::vector<uint8_t> bytes;
};

class ByteReader {
 public:
  ByteReader(const uint8_t* d, size_t n) : d_(d), n_(n) {}
  template <typename T>
  T get() {
    T v{};
    if (pos_ + sizeof(T) <= n_) std::memcpy(&v, d_ + pos_, sizeof(T));
    pos_ += sizeof(T);
    return v;
  }
  bool exact() const { return pos_ == n_; }

 private:
  const uint8_t* d_;
  size_t n_;
  size_t pos_ = 0;
};

std::array<uint32_t, 256> makeCrcTable() {
  std::array<uint32_t, 256> t{};
  for (uint32_t i = 0; i < 256; ++i) {
    uint32_t c = i;
    for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    t[i] = c;
  }
  return t;
}

}  // namespace

uint32_t crc32(const uint8_t* data, size_t n, uint32_t crc) {
  static const std::array<uint32_t, 256> table = makeCrcTable();
  crc = ~crc;
  for (size_t i = 0; i < n; ++i) crc = table[(crc ^ data[i]) & 0xFF] ^ (crc >> 8);
  return ~crc;
}

std::vector<uint8_t> encodePenSample(const PenSample& s) {
  ByteWriter w;
  w.put(s.t_ns);
  w.put(s.x_raw), w.put(s.y_raw), w.put(s.x_mm), w.put(s.y_mm);
  w.put(s.pressure_raw), w.put(s.pressure);
  w.put(s.tilt_x_raw), w.put(s.tilt_y_raw), w.put(s.tilt_x_deg), w.put(s.tilt_y_deg);
  w.put(s.distance_raw), w.put(s.distance);
  w.put(s.buttons), w.put(uint8_t(s.tool)), w.put(s.tool_id), w.put(s.tool_serial);
  w.put(uint8_t(s.in_proximity ? 1 : 0));
  return w.bytes;
}

std::optional<PenSample> decodePenSample(const std::vector<uint8_t>& p) {
  ByteReader r(p.data(), p.size());
  PenSample s;
  s.t_ns = r.get<int64_t>();
  s.x_raw = r.get<int32_t>(), s.y_raw = r.get<int32_t>();
  s.x_mm = r.get<double>(), s.y_mm = r.get<double>();
  s.pressure_raw = r.get<int32_t>(), s.pressure = r.get<float>();
  s.tilt_x_raw = r.get<int32_t>(), s.tilt_y_raw = r.get<int32_t>();
  s.tilt_x_deg = r.get<float>(), s.tilt_y_deg = r.get<float>();
  s.distance_raw = r.get<int32_t>(), s.distance = r.get<float>();
  s.buttons = r.get<uint32_t>();
  uint8_t tool = r.get<uint8_t>();
  s.tool_id = r.get<uint32_t>(), s.tool_serial = r.get<uint64_t>();
  s.in_proximity = r.get<uint8_t>() != 0;
  if (!r.exact() || tool > uint8_t(PenTool::kEraser)) return std::nullopt;
  s.tool = PenTool(tool);
  return s;
}

std::vector<uint8_t> encodeDeviceInfo(const PenDeviceInfo& d) {
  ByteWriter w;
  w.put(d.usb_vendor), w.put(d.usb_product);
  for (char c : d.name) w.put(c);
  w.put(d.x_max), w.put(d.y_max), w.put(d.x_res), w.put(d.y_res), w.put(d.pressure_max);
  w.put(d.tilt_min), w.put(d.tilt_max), w.put(d.tilt_res), w.put(d.distance_max);
  return w.bytes;
}

std::optional<PenDeviceInfo> decodeDeviceInfo(const std::vector<uint8_t>& p) {
  ByteReader r(p.data(), p.size());
  PenDeviceInfo d;
  d.usb_vendor = r.get<uint16_t>(), d.usb_product = r.get<uint16_t>();
  for (char& c : d.name) c = r.get<char>();
  d.name[sizeof(d.name) - 1] = 0;
  d.x_max = r.get<int32_t>(), d.y_max = r.get<int32_t>();
  d.x_res = r.get<double>(), d.y_res = r.get<double>();
  d.pressure_max = r.get<int32_t>();
  d.tilt_min = r.get<int32_t>(), d.tilt_max = r.get<int32_t>();
  d.tilt_res = r.get<double>();
  d.distance_max = r.get<int32_t>();
  if (!r.exact()) return std::nullopt;
  return d;
}

JournalWriter::~JournalWriter() {
  close();
}

bool JournalWriter::open(const std::string& path) {
  close();
  path_ = path;
  file_ = std::fopen(path.c_str(), "wb");
  if (!file_) {
    error_ = "journal " + path + ": cannot create: " + std::strerror(errno);
    return false;
  }
  if (!writeHeader()) return false;
  syncParentDirectory(path);
  return true;
}

bool JournalWriter::writeHeader() {
  ByteWriter w;
  for (char c : kMagic) w.put(c);
  w.put(kJournalVersion), w.put(uint32_t(0));
  if (std::fwrite(w.bytes.data(), 1, w.bytes.size(), file_) != w.bytes.size() || !sync()) {
    error_ = "journal " + path_ + ": cannot write header: " + std::strerror(errno);
    return false;
  }
  return true;
}

bool JournalWriter::openForAppend(const std::string& path, std::string* warning) {
  close();
  warning->clear();
  std::error_code ec;
  if (!std::filesystem::exists(path, ec) || std::filesystem::file_size(path, ec) < kHeaderSize)
    return open(path);
  const JournalReadResult read = readJournal(path);
  if (read.version == 0 || read.version > kJournalVersion) {
    error_ =
        read.error.empty() ? "journal " + path + ": not a journal this version writes" : read.error;
    return false;
  }
  path_ = path;
  file_ = std::fopen(path.c_str(), "r+b");
  if (!file_) {
    error_ = "journal " + path + ": cannot open for appending: " + std::strerror(errno);
    return false;
  }
  if (!read.error.empty()) {
    // Cut the torn tail so the next record follows the last whole one.
    const uint64_t size = std::filesystem::file_size(path, ec);
    if (::ftruncate(fileno(file_), off_t(read.intact_bytes)) != 0) {
      error_ = "journal " + path + ": cannot cut its damaged tail: " + std::strerror(errno);
      std::fclose(file_);
      file_ = nullptr;
      return false;
    }
    *warning = read.error + "; cut " + std::to_string(size - read.intact_bytes) +
               " bytes after the last whole record (byte " + std::to_string(read.intact_bytes) +
               ")";
  }
  if (std::fseek(file_, long(read.intact_bytes), SEEK_SET) != 0 || !sync()) {
    error_ = "journal " + path + ": cannot seek to its end: " + std::strerror(errno);
    std::fclose(file_);
    file_ = nullptr;
    return false;
  }
  return true;
}

bool JournalWriter::append(JournalRecordType type, int64_t t_ns, const uint8_t* data, size_t n) {
  if (!file_) {
    error_ = "journal: append on a closed writer";
    return false;
  }
  ByteWriter w;
  w.put(uint32_t(type)), w.put(uint32_t(n)), w.put(t_ns);
  w.bytes.insert(w.bytes.end(), data, data + n);
  w.put(crc32(w.bytes.data(), w.bytes.size()));
  if (std::fwrite(w.bytes.data(), 1, w.bytes.size(), file_) != w.bytes.size() ||
      std::fflush(file_) != 0) {
    error_ = "journal " + path_ + ": write failed: " + std::strerror(errno);
    return false;
  }
  const int64_t now = monotonicNs();
  if (unsynced_since_ns_ < 0) unsynced_since_ns_ = now;
  return syncIfDue(now);
}

bool JournalWriter::appendPenSample(const PenSample& s) {
  auto p = encodePenSample(s);
  return append(JournalRecordType::kPenSample, s.t_ns, p.data(), p.size());
}

bool JournalWriter::sync() {
  if (!file_) return false;
  if (std::fflush(file_) != 0 || ::fsync(fileno(file_)) != 0) {
    error_ = "journal " + path_ + ": sync failed: " + std::strerror(errno);
    return false;
  }
  unsynced_since_ns_ = -1;
  ++syncs_;
  return true;
}

bool JournalWriter::syncIfDue(int64_t now_ns, int64_t interval_ns) {
  if (!file_ || unsynced_since_ns_ < 0 || now_ns - unsynced_since_ns_ < interval_ns) return true;
  return sync();
}

void JournalWriter::close() {
  if (file_) {
    sync();
    std::fclose(file_);
    file_ = nullptr;
  }
}

JournalReadResult parseJournal(const uint8_t* data, size_t n, const std::string& name) {
  JournalReadResult out;
  auto fail = [&](uint64_t offset, const std::string& why) {
    out.error = name + ": byte " + std::to_string(offset) + ": " + why;
    return out;
  };
  if (n < kHeaderSize)
    return fail(0, "too short for a journal header (" + std::to_string(n) + " bytes)");
  if (std::memcmp(data, kMagic, sizeof(kMagic)) != 0)
    return fail(0, "not a cloudbrush journal (bad magic)");
  ByteReader hr(data + 8, 8);
  out.version = hr.get<uint32_t>();
  if (out.version == 0 || out.version > kJournalVersion)
    return fail(8, "unsupported journal version " + std::to_string(out.version));
  size_t pos = kHeaderSize;
  out.intact_bytes = pos;
  while (pos < n) {
    if (n - pos < kRecordHead + 4) return fail(pos, "truncated record header");
    ByteReader r(data + pos, kRecordHead);
    uint32_t type = r.get<uint32_t>();
    uint32_t len = r.get<uint32_t>();
    int64_t t_ns = r.get<int64_t>();
    if (len > kMaxPayload) return fail(pos, "record length " + std::to_string(len) + " too large");
    if (n - pos - kRecordHead < uint64_t(len) + 4) return fail(pos, "truncated record payload");
    uint32_t stored_crc;
    std::memcpy(&stored_crc, data + pos + kRecordHead + len, 4);
    if (crc32(data + pos, kRecordHead + len) != stored_crc) return fail(pos, "checksum mismatch");
    if (type >= uint32_t(JournalRecordType::kPenSample) && type <= kLastJournalRecordType) {
      JournalRecord rec;
      rec.type = JournalRecordType(type);
      rec.t_ns = t_ns;
      rec.payload.assign(data + pos + kRecordHead, data + pos + kRecordHead + len);
      out.records.push_back(std::move(rec));
    } else {
      ++out.skipped_unknown;
    }
    pos += kRecordHead + len + 4;
    out.intact_bytes = pos;
  }
  return out;
}

JournalReadResult readJournal(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    JournalReadResult r;
    r.error = path + ": cannot open: " + std::strerror(errno);
    return r;
  }
  std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                             std::istreambuf_iterator<char>());
  return parseJournal(bytes.data(), bytes.size(), path);
}

}  // namespace cb
