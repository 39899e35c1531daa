#include "app/study/bids_motion.h"

#include <algorithm>
#include <cstdio>
#include <vector>

#include "app/core/json_text.h"
#include "app/study/bids_text.h"
#include "app/study/csv_text.h"
#include "app/study/export_columns.h"

namespace cb {
namespace {

struct MotionChannel {
  const char *name, *component, *type, *tracked_point;
  const char* column;  // the samples.csv column it carries, which describes it (export_columns.h)
  const char* coding;  // how a category is written as a number, else ""
  std::string (*value)(const PenSample& s, int64_t t0_ns);
};

// One table: the channels.tsv rows and the motion.tsv columns come from it, in this order.
const std::vector<MotionChannel>& channels() {
  static const std::vector<MotionChannel> table = {
      {"latency", "n/a", "LATENCY", "n/a", "t_s", "",
       [](const PenSample& s, int64_t t0) { return bidsSeconds(elapsedNs(s.t_ns, t0)); }},
      {"pen_x", "x", "POS", "pen", "x_mm", "",
       [](const PenSample& s, int64_t) { return csvDouble(s.x_mm); }},
      {"pen_y", "y", "POS", "pen", "y_mm", "",
       [](const PenSample& s, int64_t) { return csvDouble(s.y_mm); }},
      {"tilt_x", "x", "ORNT", "pen", "tilt_x_deg", "",
       [](const PenSample& s, int64_t) { return csvFloat(s.tilt_x_deg); }},
      {"tilt_y", "y", "ORNT", "pen", "tilt_y_deg", "",
       [](const PenSample& s, int64_t) { return csvFloat(s.tilt_y_deg); }},
      {"pressure", "n/a", "MISC", "pen", "pressure", "",
       [](const PenSample& s, int64_t) { return csvFloat(s.pressure); }},
      {"distance", "n/a", "MISC", "pen", "distance", "",
       [](const PenSample& s, int64_t) { return csvFloat(s.distance); }},
      {"tip", "n/a", "MISC", "pen", "tip", "",
       [](const PenSample& s, int64_t) { return std::string(s.tipDown() ? "1" : "0"); }},
      {"in_proximity", "n/a", "MISC", "pen", "in_proximity", "",
       [](const PenSample& s, int64_t) { return std::string(s.in_proximity ? "1" : "0"); }},
      {"buttons", "n/a", "MISC", "pen", "buttons", "",
       [](const PenSample& s, int64_t) { return std::to_string(s.buttons); }},
      {"tool", "n/a", "MISC", "pen", "tool", ", written as 0 none, 1 pen, 2 eraser",
       [](const PenSample& s, int64_t) { return std::to_string(int(s.tool)); }}};
  return table;
}

int countOfType(const char* type) {
  return int(std::count_if(channels().begin(), channels().end(),
                           [&](const MotionChannel& c) { return std::string(c.type) == type; }));
}

// The tablet's report rate: 1 / the median interval between successive reports (pauses in
// proximity do not pull it down as a mean would). 0 with fewer than two distinct times.
double medianReportRateHz(const std::vector<PenSample>& samples) {
  std::vector<int64_t> intervals;
  for (size_t i = 1; i < samples.size(); ++i)
    if (samples[i].t_ns > samples[i - 1].t_ns)
      intervals.push_back(samples[i].t_ns - samples[i - 1].t_ns);
  if (intervals.empty()) return 0.0;
  std::nth_element(intervals.begin(), intervals.begin() + intervals.size() / 2, intervals.end());
  return 1e9 / double(intervals[intervals.size() / 2]);
}

std::string number(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

}  // namespace

std::string bidsMotionTsv(const SessionTrace& trace) {
  std::string out;
  out.reserve(trace.samples.size() * 96);
  for (const PenSample& s : trace.samples) {
    bool first = true;
    for (const MotionChannel& c : channels()) {
      if (!first) out += '\t';
      out += c.value(s, trace.t0_ns);
      first = false;
    }
    out += '\n';
  }
  return out;
}

std::string bidsChannelsTsv() {
  std::string out = "name\tcomponent\ttype\ttracked_point\tunits\tdescription\n";
  for (const MotionChannel& c : channels()) {
    const ExportColumn& column = exportColumn(sampleColumns(), c.column);
    const std::string units = bidsUnit(column.unit);
    out += std::string(c.name) + '\t' + c.component + '\t' + c.type + '\t' + c.tracked_point +
           '\t' + (units.empty() ? kBidsMissing : units) + '\t' +
           bidsTsvText(bidsMissingWords(column.description) + c.coding +
                       " (samples.csv: " + c.column + ")") +
           '\n';
  }
  return out;
}

std::string bidsMotionJson(const SessionTrace& trace, const std::string& task_name,
                           const std::string& task_description) {
  const std::vector<PenSample>& s = trace.samples;
  const double span_s = s.empty() ? 0.0 : double(elapsedNs(s.back().t_ns, trace.t0_ns)) * 1e-9;
  const double first_s = s.empty() ? 0.0 : double(elapsedNs(s.front().t_ns, trace.t0_ns)) * 1e-9;
  const double effective = span_s > first_s ? double(s.size() - 1) / (span_s - first_s) : 0.0;
  std::vector<std::pair<std::string, std::string>> members = {
      {"TaskName", jsonString(task_name)},
      {"TaskDescription", jsonString(task_description)},
      {"TrackingSystemName",
       jsonString(trace.device && trace.device->name[0] ? std::string(trace.device->name)
                                                        : std::string("pen tablet"))},
      {"SamplingFrequency", number(medianReportRateHz(s))},
      {"SamplingFrequencyEffective", number(effective)},
      {"RecordingDuration", number(span_s)},
      {"RecordingType", "\"continuous\""},
      {"TrackedPointsCount", "1"},
      {"MotionChannelCount", std::to_string(channels().size())},
      {"POSChannelCount", std::to_string(countOfType("POS"))},
      {"ORNTChannelCount", std::to_string(countOfType("ORNT"))},
      {"MISCChannelCount", std::to_string(countOfType("MISC"))},
      {"LATENCYChannelCount", std::to_string(countOfType("LATENCY"))},
      {"MissingValues", "\"n/a\""},
      {"SoftwareFilters", "\"n/a\""}};
  return bidsJsonObject(members);
}

}  // namespace cb
