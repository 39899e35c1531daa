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
  // Decode an all-ones and an all-zeros report of the right length under both drivers' rules;
  // under hid-input's rules every axis value lies in its logical range (clamped or ignored).
  cb::PenDeviceInfo info = cb::hid::penDeviceInfo(layout, 0x056A, 0, "fuzz");
  for (cb::PenDriverRules rules : {cb::PenDriverRules::kHidInput, cb::PenDriverRules::kWacom}) {
    cb::hid::HidPenDecoder decoder(layout, info, rules);
    for (uint8_t fill : {uint8_t{0xFF}, uint8_t{0x00}}) {
      std::vector<uint8_t> report(layout.report_bytes, fill);
      if (layout.report_id) report[0] = layout.report_id;
      cb::PenSample s;
      if (decoder.decode(report.data(), report.size(), 0, s).status !=
              cb::hid::DecodeStatus::kSample ||
          rules != cb::PenDriverRules::kHidInput || !s.in_proximity)
        continue;
      const cb::hid::FieldSlot& x = layout.x;
      if (x.logical_min < x.logical_max && s.x_raw != 0 &&
          (s.x_raw < x.logical_min || s.x_raw > x.logical_max))
        std::abort();
    }
  }
  return 0;
}
