#include "drivers/hid/hidapi_pen_source.h"

#include <fcntl.h>
#include <linux/hidraw.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <thread>

#include "drivers/core/clock.h"
#include "drivers/usb/usb_devices.h"

namespace cb::hid {
namespace {

constexpr int64_t kRescanIntervalNs = 100'000'000;  // when no device is open

int64_t nowNs() {
  return MonotonicClock().nowNs();
}

// hidapi lists nothing it cannot inspect, so a tablet behind a hidraw node this user may not
// open is invisible to it. Any such node is reported as a permission problem (like evdev, the
// node cannot be identified without opening it).
bool hidrawNodeDenied() {
  // By name rather than by listing /dev, which may itself be closed to this user.
  for (int i = 0; i < 64; ++i) {
    const std::string node = "/dev/hidraw" + std::to_string(i);
    int fd = open(node.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd >= 0)
      close(fd);
    else if (errno == EACCES || errno == EPERM)
      return true;
  }
  return false;
}

bool readHidrawDescriptor(const std::string& path, std::vector<uint8_t>& out, std::string* error,
                          bool* denied) {
  int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    *denied = errno == EACCES || errno == EPERM;
    *error = "cannot open " + path + ": " + std::strerror(errno);
    return false;
  }
  int size = 0;
  hidraw_report_descriptor rd{};
  bool ok = ioctl(fd, HIDIOCGRDESCSIZE, &size) == 0 && size > 0 && size <= HID_MAX_DESCRIPTOR_SIZE;
  if (ok) {
    rd.size = static_cast<uint32_t>(size);
    ok = ioctl(fd, HIDIOCGRDESC, &rd) == 0;
  }
  close(fd);
  if (!ok) {
    *error = "HIDIOCGRDESC failed on " + path;
    return false;
  }
  out.assign(rd.value, rd.value + rd.size);
  return true;
}

}  // namespace

bool makePenDecoder(const DeviceDatabase* devices, uint16_t vendor, uint16_t product,
                    const std::string& name, const std::vector<uint8_t>& original,
                    HidPenDevice& device, std::unique_ptr<PenDecoder>& decoder) {
  const DeviceEntry* entry = devices ? devices->find(vendor, product) : nullptr;
  device.has_entry = entry != nullptr;
  device.entry = entry ? *entry : DeviceEntry{};
  // libusb sees the device's own descriptor, hidraw the kernel driver's rewrite: the same
  // fix-ups give both the fixed one (they apply only where the original bytes still are).
  std::vector<uint8_t> descriptor = original;
  device.fixups_applied = entry ? applyReportFixups(entry->fixups, descriptor) : 0;
  ParseResult parsed = parseReportDescriptor(descriptor.data(), descriptor.size());
  const auto hasFeature = [&](uint8_t id) {
    return parsed.descriptor && parsed.descriptor->reportBytes(ReportType::kFeature, id) != 0;
  };
  // This interface has the mode report (not, e.g., a pad or touch interface of the same id).
  device.mode_report_id = entry && entry->mode_report_id && hasFeature(entry->mode_report_id)
                              ? entry->mode_report_id
                              : 0;
  if (entry && entry->protocol == PenProtocol::kIntuos4) {
    device.protocol = "intuos4";
    device.info = entry->info;
    decoder = std::make_unique<PenDecoder>(Intuos4Decoder(device.info, entry->tools));
    return true;
  }
  if (!parsed.descriptor) {
    device.error = parsed.error;
    return false;
  }
  PenLayoutResult layout = findPenLayout(*parsed.descriptor);
  if (!layout.layout) {
    device.error = layout.error;
    return false;
  }
  device.protocol = "generic";
  const std::string shown = entry && !entry->name.empty() ? entry->name : name;
  device.info = penDeviceInfo(*layout.layout, vendor, product, shown.c_str());
  decoder = std::make_unique<PenDecoder>(
      HidPenDecoder(*layout.layout, device.info, entry ? entry->rules : PenDriverRules::kHidInput,
                    entry ? entry->tools : nullptr));
  return true;
}

DecodeResult decodeReport(PenDecoder& decoder, const uint8_t* report, size_t n, int64_t t_ns,
                          PenSample& out) {
  return std::visit([&](auto& d) { return d.decode(report, n, t_ns, out); }, decoder);
}

std::string HidapiPenSource::serialNumber(std::string* why_none) const {
  if (connection_ != PenConnection::kConnected) {
    if (why_none) *why_none = std::string(backendName()) + ": no device connected";
    return "";
  }
  if (device_.serial.empty() && why_none)
    *why_none = std::string(backendName()) + ": " + device_.name + " reports no serial string";
  return device_.serial;
}

std::vector<HidPenDevice> findHidPens(HidapiLibrary& lib, uint16_t vendor,
                                      const DeviceDatabase* devices) {
  std::vector<HidPenDevice> pens;
  hid_device_info* list = lib.enumerate(vendor, 0);
  for (hid_device_info* i = list; i; i = i->next) {
    HidPenDevice d;
    d.path = i->path ? i->path : "";
    d.vendor = i->vendor_id;
    d.product = i->product_id;
    d.interface = i->interface_number;
    d.name = narrow(i->manufacturer_string);
    d.serial = narrow(i->serial_number);
    const std::string product = narrow(i->product_string);
    if (!product.empty()) d.name += (d.name.empty() ? "" : " ") + product;
    if (d.name.empty()) {  // hidapi-libusb may not read the strings; name the USB id instead
      char id[24];
      std::snprintf(id, sizeof id, "USB %04x:%04x", d.vendor, d.product);
      d.name = id;
    }
    std::vector<uint8_t> desc;
    std::string error;
    bool ok = false;
    if (lib.backend == HidapiBackend::kHidraw) {
      ok = readHidrawDescriptor(d.path, desc, &error, &d.permission_denied);
    } else {
      usb::UsbInterfaceLocation where;
      if (!usb::parseHidapiLibusbPath(d.path, where))
        error = "unrecognised hidapi-libusb path";
      else
        ok = usb::readUsbHidReportDescriptor(where, desc, &error);
      if (!ok && error.find("Access denied") != std::string::npos) d.permission_denied = true;
    }
    std::unique_ptr<PenDecoder> decoder;
    d.descriptor = desc;
    if (!ok)
      d.error = error;
    else
      makePenDecoder(devices, d.vendor, d.product, d.name, desc, d, decoder);
    pens.push_back(d);
  }
  lib.free_enumeration(list);
  return pens;
}

HidapiPenSource::HidapiPenSource(HidapiPenSourceOptions options) : options_(std::move(options)) {
  std::string error;
  lib_ = loadHidapi(options_.backend, &error);
  if (!lib_) {
    status_ = error;
    return;
  }
  hotplug_ = std::make_unique<usb::UsbHotplugWatcher>(options_.vendor);
  tryOpen();
}

HidapiPenSource::~HidapiPenSource() {
  closeDevice(nullptr);
}

void HidapiPenSource::tryOpen() {
  next_scan_ns_ = nowNs() + kRescanIntervalNs;
  if (!lib_) return;
  if (lib_->backend == HidapiBackend::kLibusb) {
    // libusb keeps its device list current through udev events; without udevd (kiosk images,
    // the test VM) a fresh context is the only way to see a replugged device.
    lib_->exit();
    lib_->init();
  }
  bool denied = false;  // a device that is a known tablet (or of the vendor asked for)
  std::string closed;   // other HID devices this user cannot open (keyboards, mice, ...)
  std::string problems;
  for (const HidPenDevice& d : findHidPens(*lib_, options_.vendor, options_.devices.get())) {
    if (!options_.path.empty() && d.path != options_.path) continue;
    // With every vendor in view, only devices a device file knows are worth a word.
    const bool known = options_.vendor != 0 || !options_.path.empty() ||
                       (options_.devices && options_.devices->find(d.vendor, d.product));
    if (d.permission_denied) {
      if (known) {
        denied = true;
      } else if (closed.size() < 80) {
        char id[16];
        std::snprintf(id, sizeof id, " %04x:%04x", d.vendor, d.product);
        closed += id;
      }
    }
    if (d.protocol.empty()) {
      if (known) problems += "; " + d.path + ": " + d.error;
      continue;
    }
    // Intuos4 USB ids expose several interfaces; the pen is the one with the mode report.
    if (d.protocol == "intuos4" && d.entry.mode_report_id != 0 && d.mode_report_id == 0) continue;
    hid_device* dev = lib_->open_path(d.path.c_str());
    if (!dev) {
      status_ = "cannot open " + d.path + " through hidapi-" + backendName() + ": " +
                narrow(lib_->error(nullptr));
      continue;
    }
    HidPenDevice device = d;
    std::unique_ptr<PenDecoder> decoder;  // fresh decoder state for every connection
    makePenDecoder(options_.devices.get(), d.vendor, d.product, d.name, d.descriptor, device,
                   decoder);
    dev_ = dev;
    device_ = device;
    decoder_ = std::move(decoder);
    // Intuos protocol: the exit packet zeroes every axis in evdev (InputFuzzFilter).
    fuzz_ = InputFuzzFilter(options_.input_fuzz ? device.entry.fuzz : AxisFuzz{},
                            device.protocol == "intuos4");
    connection_ = PenConnection::kConnected;
    status_ = "reading " + d.path + " (" + d.name + ", " + d.protocol +
              " protocol) through hidapi-" + backendName();
    if (device.has_entry) status_ += "; device file " + device.entry.where;
    if (fuzz_.fuzz().any()) status_ += "; input fuzz filter on";
    ensureTabletMode();
    return;
  }
  const bool hidden = !denied && lib_->backend == HidapiBackend::kHidraw && hidrawNodeDenied();
  connection_ = denied || hidden || !closed.empty() ? PenConnection::kPermissionDenied
                                                    : PenConnection::kSearching;
  if (denied)
    status_ = std::string("a tablet was found but cannot be opened: ") + kUdevRuleHint;
  else if (!closed.empty())
    status_ = "HID devices this user cannot open (" + closed.substr(1) +
              "); if one is the tablet: " + kUdevRuleHint;
  else if (hidden)
    status_ = std::string("hidraw nodes exist that this user cannot open: ") + kUdevRuleHint;
  else if (status_.empty() || connection_ == PenConnection::kSearching)
    status_ = std::string("no pen found through hidapi-") + backendName() + "; waiting for one" +
              problems;
}

void HidapiPenSource::ensureTabletMode() {
  // E.g. an Intuos4 starts in a mouse-compatible mode; feature report 2 = 2 selects the full
  // protocol. The kernel driver does this when it binds; without it (libusb) we do it here.
  if (!options_.switch_mode || device_.mode_report_id == 0) return;
  const uint8_t value = device_.entry.mode_value;
  unsigned char buf[2] = {device_.mode_report_id, 0};
  int n = lib_->get_feature_report(dev_, buf, sizeof buf);
  if (n >= 2 && buf[1] == value) {
    status_ += "; already in tablet mode";
    return;
  }
  const unsigned char set[2] = {device_.mode_report_id, value};
  if (lib_->send_feature_report(dev_, set, sizeof set) < 0)
    status_ += "; switching to tablet mode failed: " + narrow(lib_->error(dev_));
  else
    status_ += "; switched to tablet mode";
}

void HidapiPenSource::closeDevice(std::vector<PenSample>* out) {
  if (!dev_) return;
  if (out && decoder_) {
    PenSample s;
    const int64_t t = nowNs();
    if (std::visit([&](auto& d) { return d.disconnect(t, s); }, *decoder_)) {
      fuzz_.apply(s, device_.info);
      out->push_back(s);
    }
  }
  lib_->close(dev_);
  dev_ = nullptr;
  pen_in_proximity_ = false;
  decoder_.reset();
  connection_ = PenConnection::kSearching;
  status_ = device_.path + " went away; waiting for a pen";
}

void HidapiPenSource::poll(int timeout_ms, std::vector<PenSample>& out) {
  if (!lib_) {
    if (timeout_ms > 0) std::this_thread::sleep_for(std::chrono::milliseconds(timeout_ms));
    return;
  }
  if (!dev_) {
    const bool hotplug = hotplug_ && hotplug_->changed();
    if (hotplug || nowNs() >= next_scan_ns_) tryOpen();
    if (!dev_) {
      int wait = timeout_ms < 0 ? 50 : std::min(timeout_ms, 50);
      std::this_thread::sleep_for(std::chrono::milliseconds(wait));
      return;
    }
  }
  unsigned char buf[256];
  // The idle-proximity timer is the wacom driver's; hid-generic devices have none.
  const int64_t idle_ns = options_.idle_proximity_timeout
                              ? int64_t{device_.entry.idle_proximity_timeout_ms} * 1000000
                              : 0;
  int wait = timeout_ms;
  if (pen_in_proximity_ && idle_ns > 0) {  // wake in time for the idle-proximity timeout
    const int64_t left_ms = (last_report_ns_ + idle_ns - nowNs()) / 1000000 + 1;
    if (wait < 0 || left_ms < wait) wait = static_cast<int>(left_ms < 0 ? 0 : left_ms);
  }
  for (;;) {
    int n = lib_->read_timeout(dev_, buf, sizeof buf, wait);
    if (n < 0) {
      closeDevice(&out);
      pen_in_proximity_ = false;
      return;
    }
    if (n == 0) break;
    PenSample s;
    const int64_t t = nowNs();
    DecodeResult r = decodeReport(*decoder_, buf, static_cast<size_t>(n), t, s);
    if (r.status == DecodeStatus::kSample) {
      if (r.released) {  // the kernel's extra proximity-out frame
        fuzz_.apply(*r.released, device_.info);
        out.push_back(*r.released);
      }
      fuzz_.apply(s, device_.info);
      out.push_back(s);
      pen_in_proximity_ = s.in_proximity;
    }
    if (r.status != DecodeStatus::kRejected && r.status != DecodeStatus::kOtherReport)
      last_report_ns_ = t;
    if (r.status == DecodeStatus::kRejected) {
      ++rejected_;
      last_rejection_ = r.reason;
    }
    wait = 0;  // drain what is queued, then return
  }
  if (pen_in_proximity_ && idle_ns > 0 && nowNs() - last_report_ns_ >= idle_ns) {
    PenSample s;
    if (std::visit([&](auto& d) { return d.disconnect(nowNs(), s); }, *decoder_)) {
      fuzz_.apply(s, device_.info);
      out.push_back(s);
    }
    pen_in_proximity_ = false;
  }
}

}  // namespace cb::hid
