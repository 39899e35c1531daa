// The generic descriptor path follows the Linux kernel's HID core and hid-input for digitizers.
// Each test names the kernel source it mirrors (drivers/hid/hid-core.c, drivers/hid/hid-input.c
// in Linux 6.1 and later); the descriptors and reports are written out by hand.
#include <gtest/gtest.h>

#include "tests/unit/drivers/fixtures.h"

#include <vector>

#include "drivers/hid/hid_pen_decoder.h"
#include "drivers/hid/hid_pen_layout.h"
#include "drivers/hid/hid_report_descriptor.h"

namespace cb::hid {
namespace {

using Bytes = std::vector<uint8_t>;

Bytes cat(std::initializer_list<Bytes> parts) {
  Bytes out;
  for (const Bytes& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

// X and Y, 16 bit each, 0..4095 over 10.00 cm (exponent -2, unit cm): 41 units/mm.
const Bytes kXY = {0x05, 0x01, 0x09, 0x30, 0x09, 0x31, 0x15, 0x00, 0x26, 0xFF, 0x0F, 0x75,
                   0x10, 0x95, 0x02, 0x55, 0x0E, 0x65, 0x11, 0x35, 0x00, 0x46, 0xE8, 0x03,
                   0x81, 0x02, 0x05, 0x0D, 0x55, 0x00, 0x65, 0x00, 0x45, 0x00};
// Two state bits and six bits of padding.
Bytes stateBits(uint8_t first, uint8_t second) {
  return {0x09, first, 0x09, second, 0x15, 0x00, 0x25, 0x01, 0x75,
          0x01, 0x95,  0x02, 0x81,   0x02, 0x95, 0x06, 0x81, 0x03};
}
// Four state bits and four bits of padding.
Bytes stateBits4(uint8_t a, uint8_t b, uint8_t c, uint8_t d) {
  return {0x09, a,    0x09, b,    0x09, c,    0x09, d,    0x15, 0x00, 0x25,
          0x01, 0x75, 0x01, 0x95, 0x04, 0x81, 0x02, 0x95, 0x04, 0x81, 0x03};
}
const Bytes kStylusApplication = {0x05, 0x0D, 0x09, 0x20, 0xA1, 0x01, 0x85, 0x01};
const Bytes kPenApplication = {0x05, 0x0D, 0x09, 0x02, 0xA1, 0x01, 0x85, 0x01};
const Bytes kEnd = {0xC0};

struct Parsed {
  ReportDescriptor desc;
  PenLayout layout;
};

Parsed parsePen(const Bytes& d) {
  Parsed p;
  ParseResult r = parseReportDescriptor(d.data(), d.size());
  EXPECT_TRUE(r.descriptor) << r.error;
  if (!r.descriptor) return p;
  p.desc = *r.descriptor;
  PenLayoutResult l = findPenLayout(p.desc);
  EXPECT_TRUE(l.layout) << l.error;
  if (l.layout) p.layout = *l.layout;
  return p;
}

// Report 1: flags byte, X, Y little-endian (6 bytes).
Bytes report(uint8_t flags, uint16_t x, uint16_t y, const Bytes& tail = {}) {
  Bytes r;
  r.reserve(6 + tail.size());
  for (uint8_t b : {uint8_t{0x01}, flags, static_cast<uint8_t>(x), static_cast<uint8_t>(x >> 8),
                    static_cast<uint8_t>(y), static_cast<uint8_t>(y >> 8)})
    r.push_back(b);
  for (uint8_t b : tail) r.push_back(b);
  return r;
}

PenSample decodeOne(HidPenDecoder& d, const Bytes& r) {
  PenSample s;
  DecodeResult res = d.decode(r.data(), r.size(), 1, s);
  EXPECT_NE(res.status, DecodeStatus::kRejected) << res.reason;
  return res.status == DecodeStatus::kSample ? s : PenSample{};
}

// hid-core.c, hid_parser_global(): HID_GLOBAL_ITEM_TAG_REPORT_SIZE is refused only above 256
// bits; hid_field_extract() reads the low 32 bits of a wider field.
TEST(HidInputRules, ReportSizesUpTo256BitsAreAccepted) {
  const Bytes d = cat(
      {kPenApplication,
       stateBits(0x42, 0x32),
       kXY,
       // Transducer Serial Number, 64 bits, Logical Maximum 0xFFFFFFFF.
       {0x09, 0x5B, 0x15, 0x00, 0x27, 0xFF, 0xFF, 0xFF, 0xFF, 0x75, 0x40, 0x95, 0x01, 0x81, 0x02},
       // A 256-bit feature field (report 2), as some firmwares carry blobs.
       {0x85, 0x02, 0x06, 0x00, 0xFF, 0x09, 0x01, 0x76, 0x00, 0x01, 0x95, 0x01, 0xB1, 0x02},
       kEnd});
  Parsed p = parsePen(d);
  ASSERT_TRUE(p.layout.serial.present);
  EXPECT_EQ(p.layout.serial.bit_size, 64u);
  EXPECT_EQ(p.layout.report_bytes, 14u);
  EXPECT_EQ(p.desc.reportBytes(ReportType::kFeature, 2), 33u);
  const Bytes r =
      report(0x03, 100, 200, {0x78, 0x56, 0x34, 0x12, 0xEF, 0xCD, 0xAB, 0x89});  // serial
  EXPECT_EQ(extractBits(r.data() + 1, r.size() - 1, p.layout.serial.bit_offset, 64), 0x12345678u);
  // 257 bits is where Linux refuses ("invalid report_size").
  const Bytes too_wide = {0xA1, 0x01, 0x76, 0x01, 0x01, 0x95, 0x01, 0x81, 0x02, 0xC0};
  ParseResult bad = parseReportDescriptor(too_wide.data(), too_wide.size());
  EXPECT_FALSE(bad.descriptor);
  EXPECT_NE(bad.error.find("byte 2: report size 257 is over 256 bits"), std::string::npos)
      << bad.error;
}

// hid-input.c, hidinput_configure_usage(): digitizer usages are mapped whatever application
// collection holds them. A stylus may be its own application (Huion), a physical collection in
// a Touch Screen application (eGalax) or in an undefined one (Atmel).
TEST(HidInputRules, AStylusIsFoundInAnyCollection) {
  Parsed own = parsePen(cat({kStylusApplication, stateBits(0x42, 0x32), kXY, kEnd}));
  EXPECT_TRUE(own.layout.tip.present);
  const Bytes touchscreen =
      cat({{0x05, 0x0D, 0x09, 0x04, 0xA1, 0x01, 0x85, 0x01, 0x09, 0x20, 0xA1, 0x00},
           stateBits(0x42, 0x32),
           kXY,
           kEnd,
           kEnd});
  EXPECT_TRUE(parsePen(touchscreen).layout.in_range.present);
  const Bytes undefined_app =
      cat({{0x05, 0x0D, 0x09, 0x00, 0xA1, 0x01, 0x85, 0x01, 0x09, 0x20, 0xA1, 0x02},
           stateBits(0x42, 0x32),
           kXY,
           kEnd,
           kEnd});
  EXPECT_TRUE(parsePen(undefined_app).layout.x.present);
  // A finger in a Touch Screen is not a pen, even with Tip Switch, X and Y.
  const Bytes finger =
      cat({{0x05, 0x0D, 0x09, 0x04, 0xA1, 0x01, 0x85, 0x01, 0x09, 0x22, 0xA1, 0x02},
           stateBits(0x42, 0x32),
           kXY,
           kEnd,
           kEnd});
  ParseResult r = parseReportDescriptor(finger.data(), finger.size());
  ASSERT_TRUE(r.descriptor) << r.error;
  EXPECT_FALSE(findPenLayout(*r.descriptor).layout);
}

// hid-input.c, hidinput_configure_usage(): Tip Switch maps to BTN_TOUCH on its own; a pen
// needs no Tip Pressure (ABS_PRESSURE is simply absent).
TEST(HidInputRules, TipSwitchOnlyPen) {
  Parsed p = parsePen(cat({kStylusApplication, stateBits(0x42, 0x32), kXY, kEnd}));
  EXPECT_FALSE(p.layout.pressure.present);
  const PenDeviceInfo info = penDeviceInfo(p.layout, 0x1234, 0x5678, "tip only");
  EXPECT_EQ(info.pressure_max, 0);
  HidPenDecoder d(p.layout, info);
  PenSample hover = decodeOne(d, report(0x02, 10, 20));
  EXPECT_TRUE(hover.in_proximity);
  EXPECT_FALSE(hover.tipDown());
  PenSample touch = decodeOne(d, report(0x03, 11, 21));
  EXPECT_TRUE(touch.tipDown());
  EXPECT_EQ(touch.pressure_raw, 0);
  EXPECT_EQ(touch.pressure, 0.0f);
  EXPECT_EQ(touch.tool, PenTool::kPen);
  EXPECT_EQ(touch.x_raw, 11);
  PenSample out;
  const Bytes leave = report(0x00, 11, 21);
  ASSERT_EQ(d.decode(leave.data(), leave.size(), 2, out).status, DecodeStatus::kSample);
  EXPECT_FALSE(out.in_proximity);
}

// hid-input.c, hidinput_hid_event(): "Ignore out-of-range values as per HID specification,
// section 5.10 and 6.2.25, when NULL state bit is present. When it's not, clamp the value".
TEST(HidInputRules, NullStateValuesAreIgnoredAndOthersClamped) {
  Bytes xy_null = kXY;
  xy_null[25] = 0x42;  // Input (Data, Var, Abs, Null State)
  const Bytes pressure = {0x09, 0x30, 0x15, 0x00, 0x26, 0xFF, 0x03,
                          0x75, 0x10, 0x95, 0x01, 0x81, 0x02};  // 0..1023 in 16 bits
  const Bytes tilt = {0x09, 0x3D, 0x15, 0xC4, 0x25, 0x3C,
                      0x75, 0x08, 0x95, 0x01, 0x81, 0x02};  // -60..60 in 8 bits
  Parsed p =
      parsePen(cat({kStylusApplication, stateBits(0x42, 0x32), xy_null, pressure, tilt, kEnd}));
  ASSERT_TRUE(p.layout.x.null_state);
  ASSERT_FALSE(p.layout.pressure.null_state);
  HidPenDecoder d(p.layout, penDeviceInfo(p.layout, 0x1234, 0x5678, "null"));
  PenSample a = decodeOne(d, report(0x03, 1000, 2000, {0x00, 0x02, 0x0A}));
  EXPECT_EQ(a.x_raw, 1000);
  EXPECT_EQ(a.pressure_raw, 512);
  EXPECT_EQ(a.tilt_x_raw, 10);
  // X = 0xFFFF is outside 0..4095 with a Null State: ignored, X stays 1000; Y moves on.
  // Pressure 0xFFFF clamps to 1023 (1.0); tilt -128 clamps to -60.
  PenSample b = decodeOne(d, report(0x03, 0xFFFF, 2100, {0xFF, 0xFF, 0x80}));
  EXPECT_EQ(b.x_raw, 1000);
  EXPECT_EQ(b.y_raw, 2100);
  EXPECT_EQ(b.pressure_raw, 1023);
  EXPECT_FLOAT_EQ(b.pressure, 1.0f);
  EXPECT_EQ(b.tilt_x_raw, -60);
  // Y = 4096 is just past the maximum: ignored as well.
  PenSample c = decodeOne(d, report(0x03, 1100, 4096, {0x00, 0x00, 0x00}));
  EXPECT_EQ(c.x_raw, 1100);
  EXPECT_EQ(c.y_raw, 2100);
}

// hid-input.c, hidinput_hid_event(), case HID_DG_ERASER: "if eraser is set, we must enforce
// BTN_TOOL_RUBBER to accommodate for devices not following the spec"; the Eraser usage is
// BTN_TOUCH (hidinput_configure_usage, 0x45), and without Invert (HID_QUIRK_NOINVERT) the
// rubber is released once Eraser and the touch are both off.
TEST(HidInputRules, EraserWithoutInvertIsTheRubber) {
  // Tip Switch, Barrel Switch, Eraser, In Range (an XP-Pen Artist 24 has this set).
  Parsed p = parsePen(cat({kPenApplication,
                           {0x09, 0x20, 0xA1, 0x00},
                           stateBits4(0x42, 0x44, 0x45, 0x32),
                           kXY,
                           kEnd,
                           kEnd}));
  ASSERT_TRUE(p.layout.eraser.present);
  ASSERT_FALSE(p.layout.invert.present);
  HidPenDecoder d(p.layout, penDeviceInfo(p.layout, 0x28BD, 0x093A, "eraser"));
  constexpr uint8_t kTip = 1, kBarrel = 2, kEraser = 4, kInRange = 8;
  PenSample hover = decodeOne(d, report(kInRange, 5, 5));
  EXPECT_EQ(hover.tool, PenTool::kPen);
  // The upper button reported as Eraser while hovering: rubber, and Eraser is BTN_TOUCH.
  PenSample erase = decodeOne(d, report(kInRange | kEraser, 6, 6));
  EXPECT_EQ(erase.tool, PenTool::kEraser);
  EXPECT_TRUE(erase.tipDown());
  // Eraser released: first the touch goes, the rubber stays one more report ...
  PenSample up = decodeOne(d, report(kInRange, 7, 7));
  EXPECT_EQ(up.tool, PenTool::kEraser);
  EXPECT_FALSE(up.tipDown());
  // ... then the kernel releases the rubber (an extra EV_SYN: a proximity-out frame at the last
  // position) and In Range brings the pen back in the same report.
  const Bytes back_report = report(kInRange | kBarrel, 8, 8);
  PenSample back;
  DecodeResult r = d.decode(back_report.data(), back_report.size(), 1, back);
  ASSERT_EQ(r.status, DecodeStatus::kSample);
  ASSERT_TRUE(r.released);
  EXPECT_FALSE(r.released->in_proximity);
  EXPECT_EQ(r.released->x_raw, 7);
  EXPECT_EQ(r.released->tool, PenTool::kEraser);
  EXPECT_EQ(back.tool, PenTool::kPen);
  EXPECT_EQ(back.x_raw, 8);
  EXPECT_EQ(back.buttons, static_cast<uint32_t>(kPenStylus1));
  EXPECT_FALSE(decodeOne(d, report(kInRange, 8, 8)).tipDown());
  // A tip switch is ignored while the rubber is the tool.
  decodeOne(d, report(kInRange | kEraser, 9, 9));
  PenSample both = decodeOne(d, report(kInRange | kEraser | kTip, 9, 9));
  EXPECT_EQ(both.tool, PenTool::kEraser);
  EXPECT_TRUE(both.tipDown());
}

// hid-input.c, hidinput_hid_event(), case HID_DG_INVERT: Invert selects the rubber while
// hovering (no touch); releasing Invert with nothing else active releases it.
TEST(HidInputRules, InvertSelectsTheRubberWhileHovering) {
  Parsed p = parsePen(cat({kStylusApplication, stateBits4(0x42, 0x3C, 0x45, 0x32), kXY, kEnd}));
  HidPenDecoder d(p.layout, penDeviceInfo(p.layout, 0x1B96, 0x0C01, "invert"));
  constexpr uint8_t kInvert = 2, kEraser = 4, kInRange = 8;
  PenSample hover = decodeOne(d, report(kInRange | kInvert, 1, 1));
  EXPECT_EQ(hover.tool, PenTool::kEraser);
  EXPECT_FALSE(hover.tipDown());
  PenSample erasing = decodeOne(d, report(kInRange | kInvert | kEraser, 1, 1));
  EXPECT_EQ(erasing.tool, PenTool::kEraser);
  EXPECT_TRUE(erasing.tipDown());
  PenSample pen = decodeOne(d, report(kInRange, 1, 1));
  EXPECT_EQ(pen.tool, PenTool::kPen);
}

// hid-input.c, hidinput_configure_usage() sets HID_QUIRK_NOTOUCH for Tip Pressure without a
// Tip Switch; hidinput_hid_event(), case HID_DG_TIPPRESSURE, then touches once pressure passes
// a + ((b - a) >> 3), and the touch lasts until the tool is released.
TEST(HidInputRules, PressureWithoutTipSwitchTouchesPastAnEighth) {
  const Bytes pressure = {0x09, 0x30, 0x15, 0x00, 0x26, 0xFF, 0x03,
                          0x75, 0x10, 0x95, 0x01, 0x81, 0x02};  // 0..1023: threshold 127
  Parsed p = parsePen(cat({kStylusApplication, stateBits(0x32, 0x44), kXY, pressure, kEnd}));
  ASSERT_FALSE(p.layout.tip.present);
  HidPenDecoder d(p.layout, penDeviceInfo(p.layout, 0x1234, 0x5678, "no tip"));
  EXPECT_FALSE(decodeOne(d, report(0x01, 1, 1, {127, 0})).tipDown()) << "127 is not past 127";
  EXPECT_TRUE(decodeOne(d, report(0x01, 1, 1, {128, 0})).tipDown());
  EXPECT_TRUE(decodeOne(d, report(0x01, 1, 1, {0, 0})).tipDown()) << "kept until release";
  PenSample out;
  const Bytes leave = report(0x00, 1, 1, {0, 0});
  ASSERT_EQ(d.decode(leave.data(), leave.size(), 2, out).status, DecodeStatus::kSample);
  EXPECT_FALSE(out.in_proximity);
  EXPECT_FALSE(decodeOne(d, report(0x01, 1, 1, {0, 0})).tipDown());
}

// The Wacom driver keeps its own rules (wacom_wac_pen_report): Eraser is contact, the tool is
// fixed on entering range; values are not clamped.
TEST(HidInputRules, WacomRulesAreKeptForWacomDevices) {
  // config/devices/wacom-generic.toml gives every Wacom the wacom driver's rules; a vendor
  // without a device file gets hid-input's.
  EXPECT_EQ(test::shippedDevices().rulesFor(0x056A, 0x0357), PenDriverRules::kWacom);
  EXPECT_EQ(test::shippedDevices().rulesFor(0x28BD, 0x093A), PenDriverRules::kHidInput);
  Parsed p = parsePen(cat({kPenApplication,
                           {0x09, 0x20, 0xA1, 0x00},
                           stateBits4(0x42, 0x44, 0x45, 0x32),
                           kXY,
                           kEnd,
                           kEnd}));
  HidPenDecoder d(p.layout, penDeviceInfo(p.layout, 0x056A, 0x0357, "wacom"),
                  PenDriverRules::kWacom);
  decodeOne(d, report(8, 5, 5));
  PenSample erase = decodeOne(d, report(8 | 4, 6, 6));
  EXPECT_EQ(erase.tool, PenTool::kPen);
  EXPECT_TRUE(erase.tipDown());
}

// hid-input.c, hidinput_calc_abs_res(): (logical extent) / (physical extent * 10^exponent),
// cm and inch converted to mm, degrees to radians (x 57.3), 32-bit arithmetic in which a
// product that wraps below its previous value gives 0, rounded to the closest.
TEST(HidInputRules, ResolutionAsTheKernelComputesIt) {
  Parsed p = parsePen(cat({kStylusApplication, stateBits(0x42, 0x32), kXY, kEnd}));
  EXPECT_EQ(kernelResolution(p.layout.x, false), 41);  // 4095 over 10.00 cm = 40.95 /mm
  FieldSlot s;
  s.logical_max = 32767;
  s.physical_max = 1000;  // 10.00 inch (exponent -2)
  s.unit = 0x13;
  s.unit_exponent = -2;
  EXPECT_EQ(kernelResolution(s, false), 129);  // 32767*1000 / (1000*254) = 129.0
  s.unit = 0x14;                               // degrees, for a tilt
  s.logical_min = -60;
  s.logical_max = 60;
  s.physical_min = -60;
  s.physical_max = 60;
  s.unit_exponent = 0;
  EXPECT_EQ(kernelResolution(s, true), 57);  // 120*573 / (120*10) = 57.3
  // No resolution when the descriptor gives none: no unit, or no physical extent (the kernel
  // does not fall back to the logical extent, HID 1.11 §6.2.2.7 notwithstanding).
  FieldSlot none = p.layout.x;
  none.unit = 0;
  EXPECT_EQ(kernelResolution(none, false), 0);
  const Bytes no_physical = {0x05, 0x0D, 0x09, 0x20, 0xA1, 0x01, 0x85, 0x01, 0x09, 0x42, 0x09, 0x32,
                             0x15, 0x00, 0x25, 0x01, 0x75, 0x01, 0x95, 0x02, 0x81, 0x02, 0x95, 0x06,
                             0x81, 0x03, 0x05, 0x01, 0x09, 0x30, 0x09, 0x31, 0x26, 0xFF, 0x0F, 0x75,
                             0x10, 0x95, 0x02, 0x55, 0x0E, 0x65, 0x11, 0x81, 0x02, 0xC0};
  Parsed q = parsePen(no_physical);
  EXPECT_EQ(q.layout.x.physical_max, 0);
  EXPECT_EQ(kernelResolution(q.layout.x, false), 0);
  EXPECT_EQ(penDeviceInfo(q.layout, 1, 2, "").x_res, 0.0);
  // 10^9 units over 1 unit of 10^-2 cm: one x10 remains after cm -> mm, and 10^10 wraps to
  // 1410065408, which is larger than before, so the kernel does not notice and keeps it.
  FieldSlot wrap;
  wrap.logical_max = 1000000000;
  wrap.physical_max = 1;
  wrap.unit = 0x11;
  wrap.unit_exponent = -2;
  EXPECT_EQ(kernelResolution(wrap, false), 1410065408);
  // x 254 wrapping below the previous value gives 0.
  FieldSlot inch_overflow;
  inch_overflow.logical_max = 100;
  inch_overflow.physical_max = 20000000;
  inch_overflow.unit = 0x13;
  EXPECT_EQ(kernelResolution(inch_overflow, false), 0);
}

// hid-core.c, hid_concatenate_last_usage_page(): at a main item the last Usage Page applies to
// the short usages declared before it. Here X (declared on Generic Desktop) becomes Digitizer
// 0x30, Tip Pressure, because Usage Page (Digitizer) comes between it and the Input item.
TEST(HidInputRules, LastUsagePageAppliesAtTheMainItem) {
  const Bytes d = {0x05, 0x0D, 0x09, 0x20, 0xA1, 0x01, 0x05, 0x01, 0x09, 0x30, 0x05, 0x0D,
                   0x15, 0x00, 0x25, 0x7F, 0x75, 0x08, 0x95, 0x01, 0x81, 0x02, 0xC0};
  ParseResult r = parseReportDescriptor(d.data(), d.size());
  ASSERT_TRUE(r.descriptor) << r.error;
  EXPECT_EQ(r.descriptor->fields[0].usages[0], pen_usage::kTipPressure);
  // An extended (4-byte) usage keeps its own page.
  const Bytes e = {0x05, 0x0D, 0x09, 0x20, 0xA1, 0x01, 0x0B, 0x30, 0x00, 0x01, 0x00, 0x05,
                   0x0D, 0x15, 0x00, 0x25, 0x7F, 0x75, 0x08, 0x95, 0x01, 0x81, 0x02, 0xC0};
  r = parseReportDescriptor(e.data(), e.size());
  ASSERT_TRUE(r.descriptor) << r.error;
  EXPECT_EQ(r.descriptor->fields[0].usages[0], pen_usage::kX);
}

// hid-core.c, hid_parser_local(), HID_LOCAL_ITEM_TAG_DELIMITER: only the first delimited set of
// usages counts ("alternative usage ignored"); hid_add_field() needs no enclosing collection.
TEST(HidInputRules, DelimitersAndFieldsOutsideCollections) {
  const Bytes d = {0x05, 0x0D, 0xA9, 0x01, 0x09, 0x42, 0xA9, 0x00, 0xA9, 0x01, 0x09, 0x45,
                   0xA9, 0x00, 0x15, 0x00, 0x25, 0x01, 0x75, 0x01, 0x95, 0x01, 0x81, 0x02};
  ParseResult r = parseReportDescriptor(d.data(), d.size());
  ASSERT_TRUE(r.descriptor) << r.error;
  ASSERT_EQ(r.descriptor->fields[0].usages.size(), 1u);
  EXPECT_EQ(r.descriptor->fields[0].usages[0], pen_usage::kTipSwitch);
  EXPECT_EQ(r.descriptor->fields[0].application, 0u);
}

}  // namespace
}  // namespace cb::hid
