#include "tests/hil/tablet/uclogic_models.h"

#include <linux/usb/ch9.h>

#include <fstream>
#include <initializer_list>
#include <iterator>

namespace cb::hil {
namespace {

std::vector<uint8_t> readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void putLe(std::vector<uint8_t>& b, size_t at, int32_t v, int bytes) {
  for (int i = 0; i < bytes; ++i) b[at + i] = (v >> (8 * i)) & 0xFF;
}

// A vendor string descriptor that carries binary parameters: bLength, STRING, then each field
// (byte offset, value, little-endian width in bytes); every other byte zero.
struct Field {
  size_t at;
  int32_t value;
  int bytes;
};
std::vector<uint8_t> parameterString(size_t length, std::initializer_list<Field> fields) {
  std::vector<uint8_t> b(length, 0);
  b[0] = static_cast<uint8_t>(length);
  b[1] = USB_DT_STRING;
  for (const Field& f : fields) putLe(b, f.at, f.value, f.bytes);
  return b;
}

std::vector<uint8_t> stringDescriptor(const std::string& ascii) {
  std::vector<uint8_t> b = {static_cast<uint8_t>(2 + 2 * ascii.size()), USB_DT_STRING};
  for (char c : ascii) b.insert(b.end(), {static_cast<uint8_t>(c), 0});
  return b;
}

const ControlRecord* findGetDescriptor(const std::vector<ControlRecord>& log, uint8_t type,
                                       uint16_t value) {
  for (const ControlRecord& r : log)
    if (r.request_type == type && r.request == USB_REQ_GET_DESCRIPTOR && r.value == value)
      return &r;
  return nullptr;
}

// ---- Huion v2: 256c:006e ------------------------------------------------------------------
// Huion's vendor id and the product id hid-uclogic lists as USB_DEVICE_ID_HUION_TABLET
// (drivers/hid/hid-ids.h), shared by the H610 Pro, Gaomon S56K and others;
// uclogic_params_init sends it to uclogic_params_huion_init.
// String 201: the firmware name uclogic_params_huion_init reads with usb_string(); only
// "HUION_T153_160607" (a transition firmware) keeps it from probing the v2 parameters. This
// one says what it is.
const char* const kHuionFirmware = "CBHIL_EMULATED_V2";
// The v2 parameters (string 200, read by uclogic_params_pen_init_v2 with wLength 32 and langid
// 0x0409; at least 18 bytes, not all UTF-16 text): X and Y logical maxima (24 bit at bytes 2
// and 5), pressure maximum (16 bit at 8), resolution in lines per inch (16 bit at 10). Both
// maxima above 65535, so every far position needs the high bytes the driver moves
// (fragmented_hires); 5080 lpi, as in the HS610 block hid-uclogic quotes
// (uclogic_params_huion_init, touch_ring_model_params_buf). Bytes after 12 are zero.
constexpr int32_t kHuionX = 120000, kHuionY = 75000, kHuionPressure = 8191, kLpi = 5080;

std::vector<uint8_t> huionParameters() {
  return parameterString(19,
                         {{2, kHuionX, 3}, {5, kHuionY, 3}, {8, kHuionPressure, 2}, {10, kLpi, 2}});
}

// The raw vendor pen report a v2 tablet sends, in the byte order uclogic_raw_event_pen
// (hid-uclogic-core.c) undoes: ID 8 (UCLOGIC_RDESC_V2_PEN_ID); state bits (tip, barrel, upper
// button; bit 7 set as the firmware does, bit 6 "in range" clear because the v2 parameters make
// the driver set it itself: UCLOGIC_PARAMS_PEN_INRANGE_NONE); X and Y low 16 bits; pressure;
// X and Y high bytes (fragmented_hires); tilt X; tilt Y the other way round (tilt_y_flipped).
// Proximity out sends nothing: the driver's 100 ms timer (uclogic_inrange_timeout) ends it.
std::optional<std::vector<uint8_t>> huionReport(const PenStep& s) {
  if (!s.sense) return std::nullopt;
  std::vector<uint8_t> r(12, 0);
  r[0] = 8;
  r[1] = 0x80 | (s.tip ? 0x01 : 0) | (s.barrel ? 0x02 : 0) | (s.barrel2 ? 0x04 : 0);
  putLe(r, 2, s.x & 0xFFFF, 2);
  putLe(r, 4, s.y & 0xFFFF, 2);
  putLe(r, 6, s.pressure, 2);
  r[8] = (s.x >> 16) & 0xFF;
  r[9] = (s.y >> 16) & 0xFF;
  r[10] = static_cast<uint8_t>(static_cast<int8_t>(s.tilt_x));
  r[11] = static_cast<uint8_t>(static_cast<int8_t>(-s.tilt_y));
  return r;
}

void checkHuionRequests(const std::vector<ControlRecord>& log, const std::vector<OutTransfer>&,
                        Checker& check) {
  const ControlRecord* v2 = findGetDescriptor(log, USB_DIR_IN, 0x0300 | 200);
  const ControlRecord* fw = findGetDescriptor(log, USB_DIR_IN, 0x0300 | 201);
  const ControlRecord* v1 = findGetDescriptor(log, USB_DIR_IN, 0x0300 | 100);
  check(fw && fw->outcome == ControlRecord::Outcome::kAnswered,
        "huion-v2: hid-uclogic read the firmware name (string 201)");
  check(v2 && v2->index == 0x0409 && v2->length == 32 &&
            v2->outcome == ControlRecord::Outcome::kAnswered && v2->data.size() == 19 &&
            (!fw || fw < v2),
        "huion-v2: hid-uclogic then read the v2 pen parameters (string 200, langid 0x0409, "
        "wLength 32; 19 bytes answered)");
  check(!v1, "huion-v2: with v2 parameters found it did not ask for the v1 ones (string 100)");
}

// ---- XP-Pen/Ugee v2: 28bd:0935 ------------------------------------------------------------
// The XP-Pen Deco L (USB_DEVICE_ID_UGEE_XPPEN_TABLET_DECO_L), one of the six ids
// uclogic_params_init sends to uclogic_params_ugee_v2_init in 6.1. That init needs the pen on
// interface 2 (interface 0 becomes the frame's mouse, 1 is ignored), sends 10 magic bytes
// (02 b0 04 00…) to interrupt OUT endpoint 0x03 (uclogic_probe_interface: a failed or short
// transfer leaves the interface "invalid", unbound), then reads string 100 with wLength 12
// and langid 0x0409 and needs exactly 12 bytes (uclogic_params_parse_ugee_v2_desc: X and Y
// logical maxima, 16 bit at 2 and 4; frame buttons at 6; frame type at 7, 0 = buttons;
// pressure maximum at 8; lines per inch at 10). A 10 x 6 in area at 5080 lpi, 8192 levels.
constexpr int32_t kUgeeX = 50800, kUgeeY = 30480, kUgeePressure = 8191;
constexpr uint8_t kUgeeButtons = 8;
const std::vector<uint8_t> kUgeeMagic = {0x02, 0xb0, 0x04, 0, 0, 0, 0, 0, 0, 0};

std::vector<uint8_t> ugeeParameters() {
  return parameterString(12, {{2, kUgeeX, 2},
                              {4, kUgeeY, 2},
                              {6, kUgeeButtons, 1},
                              {7, 0, 1},
                              {8, kUgeePressure, 2},
                              {10, kLpi, 2}});
}

// A vendor-defined interface descriptor (usage page 0xFF0A, one 11-byte input report with ID
// `id`) standing in for the tablet's own: hid-uclogic replaces interface 0's and 2's before
// any reader sees them (uclogic_report_fixup), and interface 1 stays unbound. Not a capture.
std::vector<uint8_t> vendorDescriptor(uint8_t id) {
  return {0x06, 0x0A, 0xFF, 0x09, 0x01, 0xA1, 0x01, 0x85, id,   0x15, 0x00, 0x26,
          0xFF, 0x00, 0x75, 0x08, 0x95, 0x0B, 0x09, 0x01, 0x81, 0x02, 0xC0};
}

// The pen report the ugee v2 template describes (uclogic_rdesc_ugee_v2_pen_template_arr, ID 2):
// tip, barrel, upper button (Tablet Pick), in range at bit 5 (bit 7 set as the firmware does),
// X and Y 16 bit, pressure 13 bit, tilt X and Y. The driver passes it through unchanged
// (in-range reported, no fragmented coordinates, tilt Y not flipped). Sent as the tablet sends
// it, 12 bytes: the two after the template's 10 are ignored by the kernel and by our decoder.
// Proximity out is the same report with in range clear.
std::optional<std::vector<uint8_t>> ugeeReport(const PenStep& s) {
  std::vector<uint8_t> r(12, 0);
  r[0] = 2;
  r[1] = 0x80 | (s.sense ? 0x20 : 0) | (s.tip ? 0x01 : 0) | (s.barrel ? 0x02 : 0) |
         (s.barrel2 ? 0x04 : 0);
  putLe(r, 2, s.x, 2);
  putLe(r, 4, s.y, 2);
  putLe(r, 6, s.pressure, 2);
  r[8] = static_cast<uint8_t>(static_cast<int8_t>(s.tilt_x));
  r[9] = static_cast<uint8_t>(static_cast<int8_t>(s.tilt_y));
  return r;
}

void checkUgeeRequests(const std::vector<ControlRecord>& log, const std::vector<OutTransfer>& out,
                       Checker& check) {
  size_t magic = 0;
  for (const OutTransfer& t : out) magic += t.endpoint == 0x03 && t.data == kUgeeMagic;
  check(magic == 1 && out.size() == 1,
        "ugee-v2: hid-uclogic sent the 10 magic bytes 02 b0 04 00… to interrupt OUT endpoint "
        "0x03 once (" +
            std::to_string(out.size()) + " OUT transfers)");
  const ControlRecord* p = findGetDescriptor(log, USB_DIR_IN, 0x0300 | 100);
  check(p && p->index == 0x0409 && p->length == 12 &&
            p->outcome == ControlRecord::Outcome::kAnswered && p->data.size() == 12,
        "ugee-v2: then read the pen and frame parameters (string 100, langid 0x0409, wLength "
        "12; 12 bytes answered)");
  check(!findGetDescriptor(log, USB_DIR_IN, 0x0300 | 200) &&
            !findGetDescriptor(log, USB_DIR_IN, 0x0300 | 201),
        "ugee-v2: it asked for none of Huion's strings (200, 201)");
}

// ---- Ugee v1: 28bd:0074 ------------------------------------------------------------------
// The Ugee G5 (USB_DEVICE_ID_UGEE_TABLET_G5): uclogic_params_init ignores interface 0 and
// probes interface 1 with uclogic_params_pen_init_v1, the path older Huion firmware takes too
// when string 200 is missing. It reads string 100 with wLength 12 and langid 0x0409 and needs
// exactly 12 bytes (X and Y logical maxima at 2 and 4, pressure maximum at 8, lines per inch
// at 10; bytes 6-7 unused). A 9 x 6 in area at 5080 lpi, 2048 levels: the G5's.
constexpr int32_t kUgeeV1X = 45720, kUgeeV1Y = 30480, kUgeeV1Pressure = 2047;

std::vector<uint8_t> ugeeV1Parameters() {
  return parameterString(
      12, {{2, kUgeeV1X, 2}, {4, kUgeeV1Y, 2}, {8, kUgeeV1Pressure, 2}, {10, kLpi, 2}});
}

// The v1 template's pen report (uclogic_rdesc_v1_pen_template_arr, ID 7): tip, barrel, upper
// button, in range at bit 6, X, Y and pressure 16 bit, no tilt. The firmware's in-range bit
// is inverted (set while the pen is away: UCLOGIC_PARAMS_PEN_INRANGE_INVERTED) and the driver
// flips it back (uclogic_raw_event_pen). Proximity out is the report with the bit set.
std::optional<std::vector<uint8_t>> ugeeV1Report(const PenStep& s) {
  std::vector<uint8_t> r(8, 0);
  r[0] = 7;
  r[1] = (s.sense ? 0 : 0x40) | (s.tip ? 0x01 : 0) | (s.barrel ? 0x02 : 0) | (s.barrel2 ? 0x04 : 0);
  putLe(r, 2, s.x, 2);
  putLe(r, 4, s.y, 2);
  putLe(r, 6, s.pressure, 2);
  return r;
}

void checkUgeeV1Requests(const std::vector<ControlRecord>& log, const std::vector<OutTransfer>&,
                         Checker& check) {
  const ControlRecord* p = findGetDescriptor(log, USB_DIR_IN, 0x0300 | 100);
  check(p && p->index == 0x0409 && p->length == 12 &&
            p->outcome == ControlRecord::Outcome::kAnswered && p->data.size() == 12,
        "ugee-v1: hid-uclogic read the v1 pen parameters (string 100, langid 0x0409, wLength "
        "12; 12 bytes answered)");
  check(!findGetDescriptor(log, USB_DIR_IN, 0x0300 | 200),
        "ugee-v1: it did not ask for Huion's v2 parameters (string 200)");
}

}  // namespace

UclogicModel huionV2Model(const std::string& fixture_dir) {
  UclogicModel m;
  m.name = "huion-v2";
  m.vendor = 0x256C;
  m.product = 0x006E;
  m.manufacturer = "HUION";
  m.product_name = "PenTablet";  // the HID name becomes "HUION PenTablet", as on the H610 Pro
  m.serial = "CBHIL0003";
  // The H610 Pro's interface-0 descriptor (179 bytes; provenance in tests/fixtures/hid).
  m.descriptors = {readBytes(fixture_dir + "/huion-h610-pro_256c_006e.rdesc")};
  m.vendor_string = [](uint8_t index) -> std::optional<std::vector<uint8_t>> {
    if (index == 200) return huionParameters();
    if (index == 201) return stringDescriptor(kHuionFirmware);
    return std::nullopt;  // string 100 included: the v1 parameters a v2 tablet is not asked for
  };
  m.x_max = kHuionX;
  m.y_max = kHuionY;
  m.pressure_max = kHuionPressure;
  m.tilt_min = -60;
  m.tilt_max = 60;
  m.pen_report_id = 8;
  m.x_bits = 24;
  m.report_bytes = 12;
  m.pen_node = "HUION PenTablet Pen";
  m.raw_report = huionReport;
  m.check_requests = checkHuionRequests;
  return m;
}

UclogicModel ugeeV2Model() {
  UclogicModel m;
  m.name = "ugee-v2";
  m.vendor = 0x28BD;
  m.product = 0x0935;
  m.manufacturer = "UGTABLET";
  m.product_name = "Deco L";
  m.serial = "CBHIL0004";
  m.descriptors = {vendorDescriptor(6), vendorDescriptor(5), vendorDescriptor(2)};
  m.pen_interface = 2;
  m.magic_out = true;
  m.vendor_string = [](uint8_t index) -> std::optional<std::vector<uint8_t>> {
    if (index == 100) return ugeeParameters();
    return std::nullopt;
  };
  m.x_max = kUgeeX;
  m.y_max = kUgeeY;
  m.pressure_max = kUgeePressure;
  m.tilt_min = -61;  // the template's logical range (uclogic_rdesc_ugee_v2_pen_template_arr)
  m.tilt_max = 60;
  m.pen_report_id = 2;
  m.x_bits = 16;
  m.report_bytes = 10;
  m.pen_node = "UGTABLET Deco L Pen";
  m.raw_report = ugeeReport;
  m.check_requests = checkUgeeRequests;
  return m;
}

UclogicModel ugeeV1Model() {
  UclogicModel m;
  m.name = "ugee-v1";
  m.vendor = 0x28BD;
  m.product = 0x0074;
  m.manufacturer = "UGEE";
  m.product_name = "Tablet G5";
  m.serial = "CBHIL0005";
  m.descriptors = {vendorDescriptor(3), vendorDescriptor(7)};
  m.pen_interface = 1;
  m.vendor_string = [](uint8_t index) -> std::optional<std::vector<uint8_t>> {
    if (index == 100) return ugeeV1Parameters();
    return std::nullopt;
  };
  m.x_max = kUgeeV1X;
  m.y_max = kUgeeV1Y;
  m.pressure_max = kUgeeV1Pressure;
  m.tilt = false;
  m.pen_report_id = 7;
  m.x_bits = 16;
  m.report_bytes = 8;
  m.pen_node = "UGEE Tablet G5 Pen";
  m.raw_report = ugeeV1Report;
  m.check_requests = checkUgeeV1Requests;
  return m;
}

}  // namespace cb::hil
