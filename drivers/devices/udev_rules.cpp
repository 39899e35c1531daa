#include "drivers/devices/udev_rules.h"

#include <cstdio>
#include <filesystem>
#include <set>

namespace cb {
namespace {

std::string hex4(unsigned v, bool upper) {
  char text[8];
  std::snprintf(text, sizeof text, upper ? "%04X" : "%04x", v & 0xFFFFu);
  return text;
}

// "FILE:LINE:COL" → the file's name.
std::string fileOf(const std::string& where) {
  const size_t colon = where.find(':');
  return std::filesystem::path(where.substr(0, colon)).filename().string();
}

}  // namespace

std::string udevRules(const DeviceDatabase& devices) {
  std::string out =
      "# cloudbrush: let an unprivileged kiosk user read pen tablets.\n"
      "# Generated from config/devices/*.toml by `cloudbrush devices --udev-rules`; do not edit:\n"
      "# add a device file and generate it again (tests/unit/drivers/udev_rules_test checks it).\n"
      "# Install:  sudo cp config/udev/70-cloudbrush-tablet.rules /etc/udev/rules.d/\n"
      "#           sudo udevadm control --reload && sudo udevadm trigger\n"
      "#           sudo usermod -aG input KIOSK_USER   (then log in again)\n\n"
      "# evdev nodes of tablets and pens: group input, read/write for the group (EVIOCGRAB,\n"
      "# EVIOCSCLOCKID).\n"
      "SUBSYSTEM==\"input\", KERNEL==\"event*\", ENV{ID_INPUT_TABLET}==\"1\", GROUP=\"input\", "
      "MODE=\"0660\"\n";
  // Vendors a family-wide entry covers: their models need no rules of their own.
  std::set<unsigned> whole_vendors;
  for (const DeviceEntry& e : devices.entries())
    if (!e.product) whole_vendors.insert(e.vendor);
  std::string file;
  std::set<std::pair<unsigned, int>> done;
  for (const DeviceEntry& e : devices.entries()) {
    const bool whole = !e.product;
    if (!whole && whole_vendors.count(e.vendor)) continue;
    const int product = whole ? -1 : int(*e.product);
    if (!done.insert({e.vendor, product}).second) continue;
    if (fileOf(e.where) != file) {
      file = fileOf(e.where);
      out += "\n# " + file + ": " + e.family + (whole ? " (every product)" : "") +
             " - hidraw (hidapi) and USB (libusb).\n";
    }
    const std::string hid_name =
        whole ? "*:" + hex4(e.vendor, true) + ":*"
              : "*:" + hex4(e.vendor, true) + ":" + hex4(unsigned(product), true) + ".*";
    out += "SUBSYSTEM==\"hidraw\", KERNELS==\"" + hid_name + "\", GROUP=\"input\", MODE=\"0660\"\n";
    out += "SUBSYSTEM==\"usb\", ENV{DEVTYPE}==\"usb_device\", ATTR{idVendor}==\"" +
           hex4(e.vendor, false) + "\", " +
           (whole ? "" : "ATTR{idProduct}==\"" + hex4(unsigned(product), false) + "\", ") +
           "GROUP=\"input\", MODE=\"0660\"\n";
  }
  return out;
}

}  // namespace cb
