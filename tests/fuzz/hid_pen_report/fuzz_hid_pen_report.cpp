// Fuzz target: the generic pen-report decoder with the PTH-660 layout, fed a stream of reports
// cut from the input (first byte of each chunk: its length), as hidraw/libusb would deliver.
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <optional>
#include <vector>

#include "drivers/hid/hid_pen_decoder.h"

namespace {

const cb::hid::PenLayout& layout() {
  static const cb::hid::PenLayout l = [] {
    std::ifstream in(std::string(CB_HID_FIXTURE_DIR) + "/wacom-pth660_v145.rdesc",
                     std::ios::binary);
    std::vector<uint8_t> d((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    auto r = cb::hid::parseReportDescriptor(d.data(), d.size());
    if (!r.descriptor) std::abort();
    return *cb::hid::findPenLayout(*r.descriptor).layout;
  }();
  return l;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const cb::hid::PenLayout& l = layout();
  cb::hid::HidPenDecoder decoder(l, cb::hid::penDeviceInfo(l, 0x056A, 0x0357, "fuzz"),
                                 cb::PenDriverRules::kWacom);
  cb::PenSample s;
  // The whole input as one report, then as a stream of length-prefixed reports.
  cb::hid::DecodeResult r = decoder.decode(data, size, 0, s);
  if (r.status == cb::hid::DecodeStatus::kRejected && r.reason.empty()) std::abort();
  if (r.status == cb::hid::DecodeStatus::kSample && size < l.report_bytes) std::abort();
  size_t pos = 0;
  while (pos < size) {
    const size_t n = std::min<size_t>(data[pos], size - pos - 1);
    r = decoder.decode(data + pos + 1, n, static_cast<int64_t>(pos), s);
    if (r.status == cb::hid::DecodeStatus::kSample && (s.pressure < 0 || s.pressure > 1.0001f))
      std::abort();
    pos += n + 1;
  }
  decoder.disconnect(0, s);
  return 0;
}
