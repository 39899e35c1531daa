// HID report descriptor parser (HID 1.11 §6.2.2) that accepts and rejects what the Linux kernel's
// HID core does (drivers/hid/hid-core.c: hid_open_report, hid_parser_global, hid_parser_local,
// hid_parser_main, hid_add_field): global state with push/pop, local usages, usage ranges and
// delimiters, collections, numbered reports, report sizes up to 256 bits. The result lists every
// main-item field with its bit position, so a decoder can be built from any descriptor.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace cb::hid {

enum class ReportType : uint8_t { kInput = 0, kOutput = 1, kFeature = 2 };

// Extended usage: page in the high 16 bits, usage id in the low 16 (HID 1.11 §6.2.2.8).
constexpr uint32_t usage(uint16_t page, uint16_t id) {
  return (uint32_t{page} << 16) | id;
}

namespace page {
inline constexpr uint16_t kGenericDesktop = 0x01;
inline constexpr uint16_t kButton = 0x09;
inline constexpr uint16_t kDigitizer = 0x0D;
inline constexpr uint16_t kWacomVendor = 0xFF0D;  // Wacom's vendor-defined digitizer page
}  // namespace page

// Main-item data bits (HID 1.11 §6.2.2.5).
enum FieldFlag : uint32_t {
  kFieldConstant = 1u << 0,
  kFieldVariable = 1u << 1,
  kFieldRelative = 1u << 2,
  kFieldNullState = 1u << 6,  // values outside the logical range mean "no value"
};

struct Field {
  ReportType type = ReportType::kInput;
  uint8_t report_id = 0;    // 0 when the descriptor has no report IDs
  uint32_t bit_offset = 0;  // from the start of the report payload (after the ID byte)
  uint32_t bit_size = 0;    // Report Size, 0..256 (values are read from the low 32 bits)
  uint32_t count = 0;       // Report Count
  uint32_t flags = 0;       // FieldFlag bits
  // One extended usage per element for variable fields (the last usage repeats, §6.2.2.8);
  // for array fields the list of selectable usages.
  std::vector<uint32_t> usages;
  // As the kernel stores them: a maximum is read signed only when the minimum in force is
  // negative; the physical extent is not defaulted to the logical one (both 0 when absent).
  int32_t logical_min = 0, logical_max = 0;
  int32_t physical_min = 0, physical_max = 0;
  uint32_t unit = 0;
  int32_t unit_exponent = 0;
  uint32_t application = 0;  // usage of the enclosing application collection
  uint32_t physical = 0;     // usage of the innermost physical collection, 0 if none
  uint32_t logical = 0;      // usage of the innermost logical collection, 0 if none

  bool isConstant() const { return (flags & kFieldConstant) != 0; }
  bool isVariable() const { return (flags & kFieldVariable) != 0; }
  bool hasNullState() const { return (flags & kFieldNullState) != 0; }
  bool isSigned() const { return logical_min < 0; }
  uint32_t usageAt(uint32_t i) const {
    if (usages.empty()) return 0;
    return i < usages.size() ? usages[i] : usages.back();
  }
};

struct ReportSize {
  ReportType type = ReportType::kInput;
  uint8_t report_id = 0;
  uint32_t bits = 0;  // payload bits, without the ID byte
};

struct ReportDescriptor {
  std::vector<Field> fields;
  std::vector<ReportSize> reports;
  bool numbered = false;  // reports carry a leading report-ID byte

  // Length in bytes of a report as it travels (ID byte included when numbered); 0 if absent.
  size_t reportBytes(ReportType type, uint8_t report_id) const;
};

struct ParseResult {
  std::optional<ReportDescriptor> descriptor;
  std::string error;  // why the descriptor was rejected, naming the byte offset
};

// Limits that keep hostile descriptors bounded. The kernel's own (include/linux/hid.h): a
// descriptor of at most HID_MAX_DESCRIPTOR_SIZE = 4096 bytes, a global stack of
// HID_GLOBAL_STACK_SIZE = 4, report sizes up to 256 bits and report counts up to
// HID_MAX_USAGES = 12288 (hid_parser_global). Usage ranges longer than kMaxUsagesPerItem are cut
// short, as the kernel cuts them at HID_MAX_USAGES ("ignoring exceeding usage max").
inline constexpr size_t kMaxDescriptorBytes = 4096;
inline constexpr int kMaxGlobalStackDepth = 4;
inline constexpr int kMaxCollectionDepth = 32;
inline constexpr uint32_t kMaxUsagesPerItem = 1024;
inline constexpr uint32_t kMaxReportSizeBits = 256;
inline constexpr uint32_t kMaxReportCount = 12288;
inline constexpr uint32_t kMaxReportBits = 8 * 4096;
inline constexpr size_t kMaxFields = 1024;

ParseResult parseReportDescriptor(const uint8_t* data, size_t n);

// Reads `bit_size` bits at `bit_offset` of a little-endian bit stream (HID 1.11 §8.4). Fields
// wider than 32 bits give their low 32 bits, as the kernel's hid_field_extract() does.
uint32_t extractBits(const uint8_t* payload, size_t payload_bytes, uint32_t bit_offset,
                     uint32_t bit_size);
// Sign-extends a `bits`-wide value.
int32_t signExtend(uint32_t value, uint32_t bits);

}  // namespace cb::hid
