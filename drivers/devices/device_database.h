// The device files loaded together: entries by USB id (a model's own entry before its vendor's
// family-wide one) and the tool tables they name. Built by device_file.h.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "drivers/devices/device_entry.h"

namespace cb {

class DeviceDatabase {
 public:
  // The model's entry, else its vendor's family-wide entry, else nullptr (hid-input's rules,
  // no quirks).
  const DeviceEntry* find(uint16_t vendor, uint16_t product) const;
  // The kernel driver whose rules apply to this USB id.
  PenDriverRules rulesFor(uint16_t vendor, uint16_t product) const {
    const DeviceEntry* e = find(vendor, product);
    return e ? e->rules : PenDriverRules::kHidInput;
  }
  std::shared_ptr<const ToolTable> toolTable(const std::string& name) const;

  const std::vector<DeviceEntry>& entries() const { return entries_; }
  const std::vector<std::string>& files() const { return files_; }

  // Used by the loader; `add` returns false (and says where the first one is) for a second
  // entry with the same vendor and product.
  bool add(DeviceEntry e, std::string* clash);
  void addToolTable(std::shared_ptr<const ToolTable> t) { tools_[t->name] = std::move(t); }
  void addFile(std::string path) { files_.push_back(std::move(path)); }

 private:
  std::vector<DeviceEntry> entries_;
  std::map<std::string, std::shared_ptr<const ToolTable>> tools_;
  std::vector<std::string> files_;
};

}  // namespace cb
