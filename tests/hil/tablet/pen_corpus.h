// The pen-device corpus script (tests/fixtures/hid/pen_corpus_reports.txt, written by hid-tools):
// per device its descriptor file, USB/I2C id, pen report and field ranges, and per step the raw
// report with the values it carries and the pen state it must give. Shared by the unit test
// (decoder against the script) and the HIL test (kernel evdev and hidraw against the script).
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "drivers/core/pen_sample.h"

namespace cb::hil {

struct CorpusRange {
  int32_t min = 0, max = 0;
};

struct CorpusStep {
  int line = 0;  // in pen_corpus_reports.txt
  std::string name;
  std::string expect;  // "out", "any", or '+'-joined: pen|rubber [touch] [barrel] [barrel2]
  std::map<std::string, int32_t> values;
  std::vector<uint8_t> report;

  int32_t value(const std::string& field) const;
  bool expects(const std::string& word) const;
};

struct CorpusDevice {
  std::string file;
  uint16_t vendor = 0, product = 0;
  int report_id = 0;
  size_t report_bytes = 0;
  std::map<std::string, CorpusRange> ranges;
  std::vector<CorpusStep> steps;
  bool i2c() const;  // the Elan and Goodix digitizers sit on I2C
};

// Reads the script; `error` names the file and line of the first malformed line.
std::vector<CorpusDevice> readPenCorpus(const std::string& path, std::string* error);

// What a pen state must look like after `step`: empty when `got` matches, else what differs.
// `out` steps need no proximity; `any` steps accept anything. `z_is_distance`: Generic Desktop Z
// of a Pen application is the hover distance (hid-input from Linux 6.18; older kernels report it
// as ABS_Z, which the evdev path does not read).
std::string corpusMismatch(const CorpusStep& step, const PenSample& got,
                           bool z_is_distance = false);

}  // namespace cb::hil
