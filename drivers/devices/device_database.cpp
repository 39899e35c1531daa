#include "drivers/devices/device_database.h"

namespace cb {

const DeviceEntry* DeviceDatabase::find(uint16_t vendor, uint16_t product) const {
  const DeviceEntry* family = nullptr;
  for (const DeviceEntry& e : entries_) {
    if (e.vendor != vendor) continue;
    if (e.product && *e.product == product) return &e;
    if (!e.product && !family) family = &e;
  }
  return family;
}

std::shared_ptr<const ToolTable> DeviceDatabase::toolTable(const std::string& name) const {
  auto it = tools_.find(name);
  return it == tools_.end() ? nullptr : it->second;
}

bool DeviceDatabase::add(DeviceEntry e, std::string* clash) {
  for (const DeviceEntry& o : entries_)
    if (o.vendor == e.vendor && o.product == e.product) {
      *clash = o.where;
      return false;
    }
  entries_.push_back(std::move(e));
  return true;
}

}  // namespace cb
