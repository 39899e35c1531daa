#include "drivers/hid/hid_report_descriptor.h"

#include <algorithm>
#include <array>
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
};

struct GlobalState {
  uint16_t usage_page = 0;
  int32_t logical_min = 0, logical_max = 0;
  bool logical_max_unsigned = false;  // raw value, reinterpreted once logical_min is known
  uint32_t logical_max_raw = 0, logical_max_size = 0;
  int32_t physical_min = 0, physical_max = 0;
  uint32_t physical_max_raw = 0, physical_max_size = 0;
  int32_t unit_exponent = 0;
  uint32_t unit = 0;
  uint32_t report_size = 0;
  uint32_t report_count = 0;
  uint8_t report_id = 0;
};

struct LocalState {
  std::vector<uint32_t> usages;
  bool have_min = false;
  uint32_t usage_min = 0;
  void clear() { *this = LocalState{}; }
};

struct Collection {
  uint8_t kind = 0;  // 0 physical, 1 application, 2 logical, ...
  uint32_t usage = 0;
};

std::string at(size_t offset, const char* what) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "report descriptor byte %zu: %s", offset, what);
  return buf;
}

// A usage given in a 1- or 2-byte item is on the current usage page; a 4-byte one is extended.
uint32_t extendUsage(uint32_t value, uint32_t size, uint16_t page) {
  return size == 4 ? value : usage(page, static_cast<uint16_t>(value));
}

// Logical/physical maxima are signed items, but descriptors routinely write e.g. 0xFF in one
// byte meaning 255 with a minimum of 0; the kernel's HID core reads them as unsigned then.
int32_t resolveMax(int32_t min, uint32_t raw, uint32_t size) {
  int32_t as_signed = size == 0 ? 0 : signExtend(raw, size * 8);
  if (min >= 0 && as_signed < min) return static_cast<int32_t>(raw);
  return as_signed;
}

}  // namespace

uint32_t extractBits(const uint8_t* payload, size_t payload_bytes, uint32_t bit_offset,
                     uint32_t bit_size) {
  if (bit_size == 0) return 0;
  if (bit_size > 32) bit_size = 32;
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

  size_t pos = 0;
  while (pos < n) {
    const size_t item_at = pos;
    const uint8_t prefix = data[pos++];
    if (prefix == 0xFE) {  // long item (§6.2.2.3): skipped, none are defined
      if (pos + 2 > n) {
        result.error = at(item_at, "long item header is truncated");
        return result;
      }
      size_t len = data[pos];
      pos += 2;
      if (pos + len > n) {
        result.error = at(item_at, "long item data runs past the end");
        return result;
      }
      pos += len;
      continue;
    }
    static constexpr std::array<uint32_t, 4> kSizes = {0, 1, 2, 4};
    const uint32_t size = kSizes[prefix & 0x03];
    if (pos + size > n) {
      result.error = at(item_at, "item data runs past the end of the descriptor");
      return result;
    }
    uint32_t value = 0;
    for (uint32_t i = 0; i < size; ++i) value |= uint32_t{data[pos + i]} << (8 * i);
    pos += size;
    const int32_t svalue = signExtend(value, size * 8);
    const uint8_t tag = prefix & 0xFC;

    switch (tag) {
      case kMainInput:
      case kMainOutput:
      case kMainFeature: {
        if (collections.empty()) {
          result.error = at(item_at, "main item outside any collection");
          return result;
        }
        if (global.report_size == 0 || global.report_size > 32) {
          result.error = at(item_at, "report size must be 1..32 bits");
          return result;
        }
        if (global.report_count == 0 || global.report_count > kMaxReportBits) {
          result.error = at(item_at, "report count is zero or too large");
          return result;
        }
        if (global.report_id == 0) saw_unnumbered_main = true;
        if (desc.numbered && saw_unnumbered_main) {
          result.error = at(item_at, "fields both with and without report IDs");
          return result;
        }
        const ReportType type = tag == kMainInput    ? ReportType::kInput
                                : tag == kMainOutput ? ReportType::kOutput
                                                     : ReportType::kFeature;
        auto it = std::find_if(desc.reports.begin(), desc.reports.end(), [&](const ReportSize& r) {
          return r.type == type && r.report_id == global.report_id;
        });
        if (it == desc.reports.end()) {
          desc.reports.push_back({type, global.report_id, 0});
          it = desc.reports.end() - 1;
        }
        const uint32_t bits = global.report_size * global.report_count;
        if (it->bits + bits > kMaxReportBits) {
          result.error = at(item_at, "report is longer than 4096 bytes");
          return result;
        }
        Field f;
        f.type = type;
        f.report_id = global.report_id;
        f.bit_offset = it->bits;
        f.bit_size = global.report_size;
        f.count = global.report_count;
        f.flags = value;
        f.usages = local.usages;
        f.logical_min = global.logical_min;
        f.logical_max =
            resolveMax(global.logical_min, global.logical_max_raw, global.logical_max_size);
        f.physical_min = global.physical_min;
        f.physical_max =
            resolveMax(global.physical_min, global.physical_max_raw, global.physical_max_size);
        if (f.physical_min == 0 && f.physical_max == 0) {  // §6.2.2.7: default to logical
          f.physical_min = f.logical_min;
          f.physical_max = f.logical_max;
        }
        f.unit = global.unit;
        f.unit_exponent = global.unit_exponent;
        for (const Collection& c : collections) {
          if (c.kind == 1) f.application = c.usage;
          if (c.kind == 0) f.physical = c.usage;
        }
        it->bits += bits;
        if (desc.fields.size() >= kMaxFields) {
          result.error = at(item_at, "more than 1024 fields");
          return result;
        }
        desc.fields.push_back(std::move(f));
        local.clear();
        break;
      }
      case kMainCollection: {
        if (static_cast<int>(collections.size()) >= kMaxCollectionDepth) {
          result.error = at(item_at, "collections nested too deeply");
          return result;
        }
        Collection c;
        c.kind = static_cast<uint8_t>(value);
        c.usage = local.usages.empty() ? 0 : local.usages.front();
        collections.push_back(c);
        local.clear();
        break;
      }
      case kMainEndCollection:
        if (collections.empty()) {
          result.error = at(item_at, "end collection without a collection");
          return result;
        }
        collections.pop_back();
        local.clear();
        break;
      case kGlobalUsagePage:
        global.usage_page = static_cast<uint16_t>(value);
        break;
      case kGlobalLogicalMin:
        global.logical_min = svalue;
        break;
      case kGlobalLogicalMax:
        global.logical_max_raw = value;
        global.logical_max_size = size;
        break;
      case kGlobalPhysicalMin:
        global.physical_min = svalue;
        break;
      case kGlobalPhysicalMax:
        global.physical_max_raw = value;
        global.physical_max_size = size;
        break;
      case kGlobalUnitExponent:
        // §6.2.2.7: a 4-bit two's-complement nibble; larger items are plain signed values.
        global.unit_exponent = value <= 0x0F ? signExtend(value, 4) : svalue;
        break;
      case kGlobalUnit:
        global.unit = value;
        break;
      case kGlobalReportSize:
        global.report_size = value;
        break;
      case kGlobalReportCount:
        global.report_count = value;
        break;
      case kGlobalReportId:
        if (value == 0 || value > 255) {
          result.error = at(item_at, "report ID must be 1..255");
          return result;
        }
        if (saw_unnumbered_main) {
          result.error = at(item_at, "report ID after fields without one");
          return result;
        }
        desc.numbered = true;
        global.report_id = static_cast<uint8_t>(value);
        break;
      case kGlobalPush:
        if (static_cast<int>(stack.size()) >= kMaxGlobalStackDepth) {
          result.error = at(item_at, "push nested too deeply");
          return result;
        }
        stack.push_back(global);
        break;
      case kGlobalPop:
        if (stack.empty()) {
          result.error = at(item_at, "pop without push");
          return result;
        }
        global = stack.back();
        stack.pop_back();
        break;
      case kLocalUsage:
        if (local.usages.size() >= kMaxUsagesPerItem) {
          result.error = at(item_at, "too many usages for one item");
          return result;
        }
        local.usages.push_back(extendUsage(value, size, global.usage_page));
        break;
      case kLocalUsageMin:
        local.have_min = true;
        local.usage_min = extendUsage(value, size, global.usage_page);
        break;
      case kLocalUsageMax: {
        if (!local.have_min) {
          result.error = at(item_at, "usage maximum without usage minimum");
          return result;
        }
        uint32_t max = extendUsage(value, size, global.usage_page);
        if (max < local.usage_min || max - local.usage_min >= kMaxUsagesPerItem ||
            local.usages.size() + (max - local.usage_min) >= kMaxUsagesPerItem) {
          result.error = at(item_at, "usage range is inverted or too large");
          return result;
        }
        for (uint32_t u = local.usage_min; u <= max; ++u) local.usages.push_back(u);
        local.have_min = false;
        break;
      }
      default:
        // Designators, strings, delimiters and reserved tags carry nothing a decoder needs.
        if ((prefix & 0x0C) == 0x0C) {
          result.error = at(item_at, "reserved item type");
          return result;
        }
        break;
    }
  }
  if (!collections.empty()) {
    result.error = "report descriptor ends inside " + std::to_string(collections.size()) +
                   " open collection(s)";
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
