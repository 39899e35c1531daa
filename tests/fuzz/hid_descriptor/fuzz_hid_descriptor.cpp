// Fuzz target: the HID report-descriptor parser and the pen-layout search (descriptors come
// from devices, i.e. from outside). A found layout must describe fields inside its report.
#include <cstdint>
#include <cstdlib>

#include "drivers/hid/hid_pen_decoder.h"
#include "drivers/hid/hid_pen_layout.h"
#include "drivers/hid/hid_report_descriptor.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  cb::hid::ParseResult r = cb::hid::parseReportDescriptor(data, size);
  if (!r.descriptor) {
    if (r.error.empty()) std::abort();  // every rejection carries a reason
    return 0;
  }
  cb::hid::PenLayoutResult l = cb::hid::findPenLayout(*r.descriptor);
  if (!l.layout) return 0;
  const cb::hid::PenLayout& layout = *l.layout;
  const size_t payload_bits = (layout.report_bytes - (layout.report_id ? 1 : 0)) * 8;
  for (const cb::hid::FieldSlot* s : {&layout.x, &layout.y, &layout.pressure, &layout.tilt_x})
    if (s->present && s->bit_offset + s->bit_size > payload_bits) std::abort();
  // Decode the descriptor's own bytes as a report of the right length.
  cb::PenDeviceInfo info = cb::hid::penDeviceInfo(layout, 0x056A, 0, "fuzz");
  cb::hid::HidPenDecoder decoder(layout, info);
  std::vector<uint8_t> report(layout.report_bytes, 0xFF);
  if (layout.report_id) report[0] = layout.report_id;
  cb::PenSample s;
  (void)decoder.decode(report.data(), report.size(), 0, s);
  return 0;
}
