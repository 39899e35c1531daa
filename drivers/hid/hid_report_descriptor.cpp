#include "drivers/hid/hid_report_descriptor.h"

#include <algorithm>
#include <cstdio>

namespace cb::hid {
namespace {

// Item tags (HID 1.11 §6.2.2.4-§6.2.2.8), already shifted to include the item type bits.
enum : uint8_t {
  kMainInput = 0x80,
  kMainOutput = 0x90,
  kMainFeature = 0xB0,
  kMainCollection = 0xA0,
  kMainEndCollection = 0xC0,
  kGlobalUsagePage = 0x04,
  kGlobalLogicalMin = 0x14,
  kGlobalLogicalMax = 0x24,
  kGlobalPhysicalMin = 0x34,
  kGlobalPhysicalMax = 0x44,
  kGlobalUnitExponent = 0x54,
  kGlobalUnit = 0x64,
  kGlobalReportSize = 0x74,
  kGlobalReportId = 0x84,
  kGlobalReportCount = 0x94,
  kGlobalPush = 0xA4,
  kGlobalPop = 0xB4,
  kLocalUsage = 0x08,
  kLocalUsageMin = 0x18,
  kLocalUsageMax = 0x28,
  kLocalDelimiter = 0xA8,
};

enum ItemType : uint8_t { kMain = 0, kGlobal = 1, kLocal = 2, kReserved = 3 };

enum CollectionKind : uint8_t { kPhysical = 0, kApplication = 1, kLogical = 2 };

struct GlobalState {
  uint16_t usage_page = 0;
  int32_t logical_min = 0, logical_max = 0;
  int32_t physical_min = 0, physical_max = 0;
  int32_t unit_exponent = 0;
  uint32_t unit = 0;
  uint32_t report_size = 0;
  uint32_t report_count = 0;
  uint8_t report_id = 0;
};

struct LocalUsage {
  uint32_t usage = 0;
  uint32_t item_size = 0;  // 4: an extended usage that carries its own page
};

struct LocalState {
  std::vector<LocalUsage> usages;
  uint32_t usage_min = 0;
  bool have_min = false;
  int delimiter_depth = 0;
  int delimiter_branch = 0;
};

struct Collection {
  uint8_t kind = 0;
  uint32_t usage = 0;
};

std::string at(size_t offset, const std::string& what) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "report descriptor byte %zu: ", offset);
  return buf + what;
}

// A usage in a 1- or 2-byte item takes the usage page (hid-core.c: hid_add_usage, complete_usage).
uint32_t completeUsage(uint32_t value, uint16_t page) {
  return (uint32_t{page} << 16) | (value & 0xFFFF);
}

// hid-core.c: hid_concatenate_last_usage_page(). At a main item the last declared usage page
// applies again to the short usages declared before it, back to the first that already has it.
void concatenateLastUsagePage(LocalState& local, uint16_t page) {
  for (size_t i = local.usages.size(); i-- > 0;) {
    LocalUsage& u = local.usages[i];
    if (u.item_size > 2) continue;
    if ((u.usage >> 16) == page) break;
    u.usage = completeUsage(u.usage, page);
  }
}

// hid-core.c: hid_parser_global(), Logical/Physical Maximum: read signed only when the minimum
// in force is negative, otherwise unsigned (and stored, like the kernel, in 32 signed bits).
int32_t maximumItem(int32_t minimum, uint32_t value, uint32_t size) {
  return minimum < 0 ? signExtend(value, size * 8) : static_cast<int32_t>(value);
}

// hid-core.c: hid_add_field(), "logical range invalid".
bool logicalRangeValid(int32_t min, int32_t max) {
  return min < 0 ? max >= min : static_cast<uint32_t>(max) >= static_cast<uint32_t>(min);
}

}  // namespace

uint32_t extractBits(const uint8_t* payload, size_t payload_bytes, uint32_t bit_offset,
                     uint32_t bit_size) {
  if (bit_size == 0) return 0;
  if (bit_size > 32) bit_size = 32;  // hid_field_extract(): "called with n > 32", n = 32
  // At most five bytes hold a 32-bit field at any bit alignment; bytes past the end read as 0.
  const size_t first = bit_offset / 8, last = (size_t{bit_offset} + bit_size - 1) / 8;
  uint64_t acc = 0;
  for (size_t b = first, shift = 0; b <= last && b < payload_bytes; ++b, shift += 8)
    acc |= uint64_t{payload[b]} << shift;
  acc >>= bit_offset % 8;
  return static_cast<uint32_t>(acc & ((uint64_t{1} << bit_size) - 1));
}

int32_t signExtend(uint32_t value, uint32_t bits) {
  if (bits == 0 || bits >= 32) return static_cast<int32_t>(value);
  uint32_t sign = 1u << (bits - 1);
  value &= (1u << bits) - 1;
  return static_cast<int32_t>((value ^ sign) - sign);
}

size_t ReportDescriptor::reportBytes(ReportType type, uint8_t report_id) const {
  for (const ReportSize& r : reports)
    if (r.type == type && r.report_id == report_id) return (r.bits + 7) / 8 + (numbered ? 1 : 0);
  return 0;
}

namespace {

// One short item (HID 1.11 §6.2.2.2): where it starts, its tag and type, its data.
struct Item {
  size_t at = 0;
  uint8_t tag = 0;
  ItemType type = kMain;
  uint32_t size = 0;  // data bytes: 0, 1, 2 or 4
  uint32_t value = 0;
  int32_t svalue = 0;
};

// The parser state between items (hid-core.c: struct hid_parser). Each item kind has its own
// method, as hid_parser_main/global/local() in the kernel; each returns an error message, empty
// when the item is accepted.
class DescriptorParser {
 public:
  std::string item(const Item& it) {
    switch (it.type) {
      case kMain:
        return mainItem(it);
      case kGlobal:
        return globalItem(it);
      case kLocal:
        return localItem(it);
      case kReserved:
        return {};  // hid_parser_reserved(): ignored
    }
    return {};
  }
  // What is left open at the end of the descriptor, or why it describes nothing.
  std::string finish() const {
    if (!collections_.empty())
      return "report descriptor ends inside " + std::to_string(collections_.size()) +
             " open collection(s)";
    if (local_.delimiter_depth != 0) return "report descriptor ends inside a delimiter";
    if (desc_.fields.empty()) return "report descriptor declares no fields";
    return {};
  }
  ReportDescriptor take() { return std::move(desc_); }

 private:
  std::string mainItem(const Item& it);
  std::string field(const Item& it);
  std::string globalItem(const Item& it);
  std::string localItem(const Item& it);
  std::string usageRange(const Item& it);

  ReportDescriptor desc_;
  GlobalState global_;
  std::vector<GlobalState> stack_;
  LocalState local_;
  std::vector<Collection> collections_;
  bool saw_unnumbered_main_ = false;
};

std::string DescriptorParser::mainItem(const Item& it) {
  concatenateLastUsagePage(local_, global_.usage_page);
  switch (it.tag) {
    case kMainInput:
    case kMainOutput:
    case kMainFeature:
      if (std::string error = field(it); !error.empty()) return error;
      break;
    case kMainCollection: {
      if (static_cast<int>(collections_.size()) >= kMaxCollectionDepth)
        return at(it.at, "collections nested too deeply");
      Collection c;
      c.kind = static_cast<uint8_t>(it.value & 0xFF);
      c.usage = local_.usages.empty() ? 0 : local_.usages.front().usage;
      collections_.push_back(c);
      break;
    }
    case kMainEndCollection:
      if (collections_.empty()) return at(it.at, "end collection without a collection");
      collections_.pop_back();
      break;
    default:  // hid_parser_main(): "unknown main item tag", ignored
      break;
  }
  local_ = LocalState{};
  return {};
}

// An Input, Output or Feature item: a field appended to its report (hid-core.c:
// hid_add_field()).
std::string DescriptorParser::field(const Item& it) {
  if (!logicalRangeValid(global_.logical_min, global_.logical_max))
    return at(it.at, "logical maximum " + std::to_string(global_.logical_max) +
                         " is below logical minimum " + std::to_string(global_.logical_min));
  if (global_.report_id == 0) saw_unnumbered_main_ = true;
  if (desc_.numbered && saw_unnumbered_main_)
    return at(it.at, "fields both with and without report IDs");
  const ReportType rtype = it.tag == kMainInput    ? ReportType::kInput
                           : it.tag == kMainOutput ? ReportType::kOutput
                                                   : ReportType::kFeature;
  auto report = std::find_if(desc_.reports.begin(), desc_.reports.end(), [&](const ReportSize& r) {
    return r.type == rtype && r.report_id == global_.report_id;
  });
  if (report == desc_.reports.end()) {
    desc_.reports.push_back({rtype, global_.report_id, 0});
    report = desc_.reports.end() - 1;
  }
  const uint64_t bits = uint64_t{global_.report_size} * global_.report_count;
  if (report->bits + bits > kMaxReportBits) return at(it.at, "report is longer than 4096 bytes");
  if (desc_.fields.size() >= kMaxFields) return at(it.at, "more than 1024 fields");
  Field f;
  f.type = rtype;
  f.report_id = global_.report_id;
  f.bit_offset = report->bits;
  f.bit_size = global_.report_size;
  f.count = global_.report_count;
  f.flags = it.value;
  f.usages.reserve(local_.usages.size());
  for (const LocalUsage& u : local_.usages) f.usages.push_back(u.usage);
  f.logical_min = global_.logical_min;
  f.logical_max = global_.logical_max;
  f.physical_min = global_.physical_min;
  f.physical_max = global_.physical_max;
  f.unit = global_.unit;
  f.unit_exponent = global_.unit_exponent;
  for (const Collection& c : collections_) {  // innermost wins (hid_lookup_collection)
    if (c.kind == kApplication) f.application = c.usage;
    if (c.kind == kPhysical) f.physical = c.usage;
    if (c.kind == kLogical) f.logical = c.usage;
  }
  report->bits += static_cast<uint32_t>(bits);
  desc_.fields.push_back(std::move(f));
  return {};
}

std::string DescriptorParser::globalItem(const Item& it) {
  GlobalState& g = global_;
  switch (it.tag) {
    case kGlobalUsagePage:
      g.usage_page = static_cast<uint16_t>(it.value);
      break;
    case kGlobalLogicalMin:
      g.logical_min = it.svalue;
      break;
    case kGlobalLogicalMax:
      g.logical_max = maximumItem(g.logical_min, it.value, it.size);
      break;
    case kGlobalPhysicalMin:
      g.physical_min = it.svalue;
      break;
    case kGlobalPhysicalMax:
      g.physical_max = maximumItem(g.physical_min, it.value, it.size);
      break;
    case kGlobalUnitExponent:
      // A 4-bit two's-complement nibble when it fits, else a plain signed value.
      g.unit_exponent = (it.svalue & ~0x0F) == 0 ? signExtend(it.value, 4) : it.svalue;
      break;
    case kGlobalUnit:
      g.unit = it.value;
      break;
    case kGlobalReportSize:
      if (it.value > kMaxReportSizeBits)
        return at(it.at, "report size " + std::to_string(it.value) + " is over 256 bits");
      g.report_size = it.value;
      break;
    case kGlobalReportCount:
      if (it.value > kMaxReportCount)
        return at(it.at, "report count " + std::to_string(it.value) + " is over 12288");
      g.report_count = it.value;
      break;
    case kGlobalReportId:
      if (it.value == 0 || it.value > 255) return at(it.at, "report ID must be 1..255");
      if (saw_unnumbered_main_) return at(it.at, "report ID after fields without one");
      desc_.numbered = true;
      g.report_id = static_cast<uint8_t>(it.value);
      break;
    case kGlobalPush:
      if (static_cast<int>(stack_.size()) >= kMaxGlobalStackDepth)
        return at(it.at, "push nested too deeply (Linux allows 4)");
      stack_.push_back(g);
      break;
    case kGlobalPop:
      if (stack_.empty()) return at(it.at, "pop without push");
      g = stack_.back();
      stack_.pop_back();
      break;
    default:
      return at(it.at, "unknown global item tag");
  }
  return {};
}

// Local items. Usages after the first delimited set are alternatives the kernel ignores.
std::string DescriptorParser::localItem(const Item& it) {
  LocalState& l = local_;
  switch (it.tag) {
    case kLocalDelimiter:
      if (it.value != 0) {
        if (l.delimiter_depth != 0) return at(it.at, "nested delimiters");
        ++l.delimiter_depth;
        ++l.delimiter_branch;
      } else {
        if (l.delimiter_depth < 1) return at(it.at, "close delimiter without an open one");
        --l.delimiter_depth;
      }
      break;
    case kLocalUsage:
      if (l.delimiter_branch > 1) break;
      if (l.usages.size() >= kMaxUsagesPerItem) return at(it.at, "too many usages for one item");
      l.usages.push_back(
          {it.size <= 2 ? completeUsage(it.value, global_.usage_page) : it.value, it.size});
      break;
    case kLocalUsageMin:
      if (l.delimiter_branch > 1) break;
      l.have_min = true;
      l.usage_min = it.value;
      break;
    case kLocalUsageMax:
      if (l.delimiter_branch > 1) break;
      return usageRange(it);
    default:  // designators and strings carry nothing a decoder needs
      break;
  }
  return {};
}

// Usage Maximum closes a range opened by Usage Minimum: every usage in it is added, cut at the
// usage limit as the kernel cuts at HID_MAX_USAGES.
std::string DescriptorParser::usageRange(const Item& it) {
  LocalState& l = local_;
  if (!l.have_min) return at(it.at, "usage maximum without usage minimum");
  if (it.value < l.usage_min) return at(it.at, "usage range is inverted");
  const uint64_t room = kMaxUsagesPerItem - l.usages.size();
  const uint64_t last =
      std::min<uint64_t>(it.value, uint64_t{l.usage_min} + (room == 0 ? 0 : room - 1));
  if (room == 0) return at(it.at, "too many usages for one item");
  for (uint64_t u = l.usage_min; u <= last; ++u) {
    const auto raw = static_cast<uint32_t>(u);
    l.usages.push_back({it.size <= 2 ? completeUsage(raw, global_.usage_page) : raw, it.size});
  }
  l.have_min = false;
  return {};
}

// The next short item at `*pos`, or an error message (hid-core.c: fetch_item()).
std::string fetchItem(const uint8_t* data, size_t n, size_t* pos, Item* it) {
  it->at = *pos;
  const uint8_t prefix = data[(*pos)++];
  // fetch_item() reads every item with tag 15 as a long item, and hid_open_report() rejects the
  // descriptor on the first one ("unexpected long global item").
  if ((prefix >> 4) == 0x0F) return at(it->at, "long items are not supported (nor by Linux)");
  static constexpr uint32_t kSizes[4] = {0, 1, 2, 4};
  it->size = kSizes[prefix & 0x03];
  if (*pos + it->size > n) return at(it->at, "item data runs past the end of the descriptor");
  it->value = 0;
  for (uint32_t i = 0; i < it->size; ++i) it->value |= uint32_t{data[*pos + i]} << (8 * i);
  *pos += it->size;
  it->svalue = signExtend(it->value, it->size * 8);
  it->tag = prefix & 0xFC;
  it->type = static_cast<ItemType>((prefix >> 2) & 0x03);
  return {};
}

}  // namespace

ParseResult parseReportDescriptor(const uint8_t* data, size_t n) {
  ParseResult result;
  if (n == 0) {
    result.error = "report descriptor is empty";
    return result;
  }
  if (n > kMaxDescriptorBytes) {
    result.error = "report descriptor is longer than " + std::to_string(kMaxDescriptorBytes) +
                   " bytes (" + std::to_string(n) + ")";
    return result;
  }
  DescriptorParser parser;
  for (size_t pos = 0; pos < n;) {
    Item it;
    result.error = fetchItem(data, n, &pos, &it);
    if (result.error.empty()) result.error = parser.item(it);
    if (!result.error.empty()) return result;
  }
  result.error = parser.finish();
  if (result.error.empty()) result.descriptor = parser.take();
  return result;
}

}  // namespace cb::hid
