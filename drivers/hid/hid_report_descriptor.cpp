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
  ReportDescriptor desc;
  GlobalState global;
  std::vector<GlobalState> stack;
  LocalState local;
  std::vector<Collection> collections;
  bool saw_unnumbered_main = false;
  auto fail = [&](size_t item_at, const std::string& what) {
    result.error = at(item_at, what);
    return result;
  };

  size_t pos = 0;
  while (pos < n) {
    const size_t item_at = pos;
    const uint8_t prefix = data[pos++];
    // hid-core.c: fetch_item() reads every item with tag 15 as a long item, and
    // hid_open_report() rejects the descriptor on the first one ("unexpected long global item").
    if ((prefix >> 4) == 0x0F) return fail(item_at, "long items are not supported (nor by Linux)");
    static constexpr uint32_t kSizes[4] = {0, 1, 2, 4};
    const uint32_t size = kSizes[prefix & 0x03];
    if (pos + size > n) return fail(item_at, "item data runs past the end of the descriptor");
    uint32_t value = 0;
    for (uint32_t i = 0; i < size; ++i) value |= uint32_t{data[pos + i]} << (8 * i);
    pos += size;
    const int32_t svalue = signExtend(value, size * 8);
    const uint8_t tag = prefix & 0xFC;
    const auto type = static_cast<ItemType>((prefix >> 2) & 0x03);

    if (type == kReserved) continue;  // hid_parser_reserved(): ignored

    if (type == kMain) {
      concatenateLastUsagePage(local, global.usage_page);
      switch (tag) {
        case kMainInput:
        case kMainOutput:
        case kMainFeature: {
          if (!logicalRangeValid(global.logical_min, global.logical_max))
            return fail(item_at, "logical maximum " + std::to_string(global.logical_max) +
                                     " is below logical minimum " +
                                     std::to_string(global.logical_min));
          if (global.report_id == 0) saw_unnumbered_main = true;
          if (desc.numbered && saw_unnumbered_main)
            return fail(item_at, "fields both with and without report IDs");
          const ReportType rtype = tag == kMainInput    ? ReportType::kInput
                                   : tag == kMainOutput ? ReportType::kOutput
                                                        : ReportType::kFeature;
          auto it =
              std::find_if(desc.reports.begin(), desc.reports.end(), [&](const ReportSize& r) {
                return r.type == rtype && r.report_id == global.report_id;
              });
          if (it == desc.reports.end()) {
            desc.reports.push_back({rtype, global.report_id, 0});
            it = desc.reports.end() - 1;
          }
          const uint64_t bits = uint64_t{global.report_size} * global.report_count;
          if (it->bits + bits > kMaxReportBits)
            return fail(item_at, "report is longer than 4096 bytes");
          if (desc.fields.size() >= kMaxFields) return fail(item_at, "more than 1024 fields");
          Field f;
          f.type = rtype;
          f.report_id = global.report_id;
          f.bit_offset = it->bits;
          f.bit_size = global.report_size;
          f.count = global.report_count;
          f.flags = value;
          f.usages.reserve(local.usages.size());
          for (const LocalUsage& u : local.usages) f.usages.push_back(u.usage);
          f.logical_min = global.logical_min;
          f.logical_max = global.logical_max;
          f.physical_min = global.physical_min;
          f.physical_max = global.physical_max;
          f.unit = global.unit;
          f.unit_exponent = global.unit_exponent;
          for (const Collection& c : collections) {  // innermost wins (hid_lookup_collection)
            if (c.kind == kApplication) f.application = c.usage;
            if (c.kind == kPhysical) f.physical = c.usage;
            if (c.kind == kLogical) f.logical = c.usage;
          }
          it->bits += static_cast<uint32_t>(bits);
          desc.fields.push_back(std::move(f));
          break;
        }
        case kMainCollection: {
          if (static_cast<int>(collections.size()) >= kMaxCollectionDepth)
            return fail(item_at, "collections nested too deeply");
          Collection c;
          c.kind = static_cast<uint8_t>(value & 0xFF);
          c.usage = local.usages.empty() ? 0 : local.usages.front().usage;
          collections.push_back(c);
          break;
        }
        case kMainEndCollection:
          if (collections.empty()) return fail(item_at, "end collection without a collection");
          collections.pop_back();
          break;
        default:  // hid_parser_main(): "unknown main item tag", ignored
          break;
      }
      local = LocalState{};
      continue;
    }

    if (type == kGlobal) {
      switch (tag) {
        case kGlobalUsagePage:
          global.usage_page = static_cast<uint16_t>(value);
          break;
        case kGlobalLogicalMin:
          global.logical_min = svalue;
          break;
        case kGlobalLogicalMax:
          global.logical_max = maximumItem(global.logical_min, value, size);
          break;
        case kGlobalPhysicalMin:
          global.physical_min = svalue;
          break;
        case kGlobalPhysicalMax:
          global.physical_max = maximumItem(global.physical_min, value, size);
          break;
        case kGlobalUnitExponent:
          // A 4-bit two's-complement nibble when it fits, else a plain signed value.
          global.unit_exponent = (svalue & ~0x0F) == 0 ? signExtend(value, 4) : svalue;
          break;
        case kGlobalUnit:
          global.unit = value;
          break;
        case kGlobalReportSize:
          if (value > kMaxReportSizeBits)
            return fail(item_at, "report size " + std::to_string(value) + " is over 256 bits");
          global.report_size = value;
          break;
        case kGlobalReportCount:
          if (value > kMaxReportCount)
            return fail(item_at, "report count " + std::to_string(value) + " is over 12288");
          global.report_count = value;
          break;
        case kGlobalReportId:
          if (value == 0 || value > 255) return fail(item_at, "report ID must be 1..255");
          if (saw_unnumbered_main) return fail(item_at, "report ID after fields without one");
          desc.numbered = true;
          global.report_id = static_cast<uint8_t>(value);
          break;
        case kGlobalPush:
          if (static_cast<int>(stack.size()) >= kMaxGlobalStackDepth)
            return fail(item_at, "push nested too deeply (Linux allows 4)");
          stack.push_back(global);
          break;
        case kGlobalPop:
          if (stack.empty()) return fail(item_at, "pop without push");
          global = stack.back();
          stack.pop_back();
          break;
        default:
          return fail(item_at, "unknown global item tag");
      }
      continue;
    }

    // Local items. Usages after the first delimited set are alternatives the kernel ignores.
    switch (tag) {
      case kLocalDelimiter:
        if (value != 0) {
          if (local.delimiter_depth != 0) return fail(item_at, "nested delimiters");
          ++local.delimiter_depth;
          ++local.delimiter_branch;
        } else {
          if (local.delimiter_depth < 1)
            return fail(item_at, "close delimiter without an open one");
          --local.delimiter_depth;
        }
        break;
      case kLocalUsage:
        if (local.delimiter_branch > 1) break;
        if (local.usages.size() >= kMaxUsagesPerItem)
          return fail(item_at, "too many usages for one item");
        local.usages.push_back({size <= 2 ? completeUsage(value, global.usage_page) : value, size});
        break;
      case kLocalUsageMin:
        if (local.delimiter_branch > 1) break;
        local.have_min = true;
        local.usage_min = value;
        break;
      case kLocalUsageMax: {
        if (local.delimiter_branch > 1) break;
        if (!local.have_min) return fail(item_at, "usage maximum without usage minimum");
        if (value < local.usage_min) return fail(item_at, "usage range is inverted");
        // Cut at the usage limit, as the kernel cuts at HID_MAX_USAGES.
        const uint64_t room = kMaxUsagesPerItem - local.usages.size();
        const uint64_t last =
            std::min<uint64_t>(value, uint64_t{local.usage_min} + (room == 0 ? 0 : room - 1));
        if (room == 0) return fail(item_at, "too many usages for one item");
        for (uint64_t u = local.usage_min; u <= last; ++u) {
          const auto raw = static_cast<uint32_t>(u);
          local.usages.push_back({size <= 2 ? completeUsage(raw, global.usage_page) : raw, size});
        }
        local.have_min = false;
        break;
      }
      default:  // designators and strings carry nothing a decoder needs
        break;
    }
  }
  if (!collections.empty()) {
    result.error = "report descriptor ends inside " + std::to_string(collections.size()) +
                   " open collection(s)";
    return result;
  }
  if (local.delimiter_depth != 0) {
    result.error = "report descriptor ends inside a delimiter";
    return result;
  }
  if (desc.fields.empty()) {
    result.error = "report descriptor declares no fields";
    return result;
  }
  result.descriptor = std::move(desc);
  return result;
}

}  // namespace cb::hid
