// Pen-trace exports: InkML read back with libxml2 and samples.csv parsed here both give back
// every journal sample; strokes.csv and events.csv follow the journal's records.
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <libxml/parser.h>
#include <libxml/tree.h>

#include "app/session/synthetic_session.h"
#include "app/study/inkml_writer.h"
#include "app/study/likert_answers.h"  // splitCsvLine
#include "app/study/session_trace.h"
#include "app/study/stroke_table.h"
#include "app/study/trace_csv.h"
#include "app/study/trial_table.h"
#include "app/study/utf8_text.h"
#include "drivers/core/journal.h"
#include "drivers/core/journal_records.h"
#include "drivers/core/pen_units.h"

namespace cb {
namespace {

constexpr int kW = 640, kH = 400;

std::string tempPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() /
          ("cb_study_" + std::to_string(::getpid()) + "_" + name))
      .string();
}

// A journal like the painter's: device, session, mode, brush, two strokes with a brush change
// and a marker between them. Returns the samples written.
std::vector<PenSample> writeJournal(const std::string& path, int64_t t0) {
  JournalWriter journal;
  EXPECT_TRUE(journal.open(path)) << journal.error();
  const PenDeviceInfo tablet = syntheticTablet(kW, kH);
  const std::vector<uint8_t> device = encodeDeviceInfo(tablet);
  journal.append(JournalRecordType::kDevice, t0, device.data(), device.size());
  journal.append(JournalRecordType::kSession, t0, "format = 2\ngrid = 64\n");
  journal.append(JournalRecordType::kMode, t0 + 1000, "paint");
  journal.append(JournalRecordType::kUi, t0 + 2000, "brush=3d");
  std::vector<PenSample> written;
  const std::vector<SyntheticStroke> strokes = referencePaintStrokes(kW, kH);
  int64_t t = t0 + 10'000'000;
  for (size_t k = 0; k < 2 && k < strokes.size(); ++k) {
    if (k == 1) {
      journal.append(JournalRecordType::kUi, t, "brush=2d");
      journal.append(JournalRecordType::kMarker, t, "task 1, stroke boundary, \"quoted\"");
    }
    for (const PenSample& s : syntheticPenSamples(strokes[k], tablet, kW, kH, 200.0, t)) {
      EXPECT_TRUE(journal.appendPenSample(s));
      written.push_back(s);
      t = s.t_ns + 5'000'000;
    }
  }
  journal.append(JournalRecordType::kUi, t, "undo");
  journal.close();
  return written;
}

std::vector<std::string> split(const std::string& text, char sep) {
  std::vector<std::string> parts;
  std::stringstream s(text);
  std::string part;
  while (std::getline(s, part, sep)) parts.push_back(part);
  return parts;
}

// "12.345678" (exact decimal with `digits` places) as an integer count of 10^-digits units.
int64_t exactDecimal(const std::string& text, int digits) {
  const size_t dot = text.find('.');
  EXPECT_NE(dot, std::string::npos) << text;
  EXPECT_EQ(text.size() - dot - 1, size_t(digits)) << text;
  const bool negative = text[0] == '-';
  int64_t whole = std::llabs(std::stoll(text.substr(0, dot)));
  int64_t frac = std::stoll(text.substr(dot + 1));
  int64_t scale = 1;
  for (int i = 0; i < digits; ++i) scale *= 10;
  return (negative ? -1 : 1) * (whole * scale + frac);
}

double toDouble(const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  EXPECT_EQ(*end, 0) << text;
  return v;
}
float toFloat(const std::string& text) {
  char* end = nullptr;
  const float v = std::strtof(text.c_str(), &end);
  EXPECT_EQ(*end, 0) << text;
  return v;
}

std::string attr(xmlNode* node, const char* name) {
  xmlChar* v = xmlGetProp(node, reinterpret_cast<const xmlChar*>(name));
  std::string s = v ? reinterpret_cast<const char*>(v) : "";
  xmlFree(v);
  return s;
}
bool named(xmlNode* node, const char* name) {
  return node->type == XML_ELEMENT_NODE &&
         xmlStrcmp(node->name, reinterpret_cast<const xmlChar*>(name)) == 0;
}
void collect(xmlNode* node, const char* name, std::vector<xmlNode*>* out) {
  for (xmlNode* n = node; n; n = n->next) {
    if (named(n, name)) out->push_back(n);
    collect(n->children, name, out);
  }
}

class TraceExport : public ::testing::Test {
 protected:
  void SetUp() override {
    path_ = tempPath("a.cbj");
    samples_ = writeJournal(path_, 5'000'000'000);
    trace_ = loadSessionTrace(path_);
  }
  void TearDown() override { std::filesystem::remove(path_); }
  std::string path_;
  std::vector<PenSample> samples_;
  SessionTrace trace_;
};

TEST_F(TraceExport, TraceHoldsEverySampleAndEvent) {
  ASSERT_EQ(trace_.samples.size(), samples_.size());
  ASSERT_GT(samples_.size(), 20u);
  ASSERT_TRUE(trace_.device.has_value());
  EXPECT_EQ(trace_.t0_ns, 5'000'000'000);
  EXPECT_TRUE(trace_.journal_warning.empty());
  for (size_t i = 0; i < samples_.size(); ++i) {
    ASSERT_TRUE(samePenState(trace_.samples[i], samples_[i])) << i;
    ASSERT_EQ(trace_.samples[i].t_ns, samples_[i].t_ns);
  }
  // device, session, mode, brush, brush, marker, undo
  EXPECT_EQ(trace_.events.size(), 7u);
}

TEST_F(TraceExport, InkmlIsWellFormedWithDeclaredChannelsAndRoundTrips) {
  std::ostringstream out;
  writeInkml(out, {trace_});
  const std::string text = out.str();
  xmlDoc* doc = xmlReadMemory(text.data(), int(text.size()), "traces.inkml", nullptr,
                              XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING);
  ASSERT_NE(doc, nullptr) << "not well-formed XML";
  xmlNode* root = xmlDocGetRootElement(doc);
  ASSERT_TRUE(named(root, "ink"));
  ASSERT_NE(root->ns, nullptr);
  EXPECT_STREQ(reinterpret_cast<const char*>(root->ns->href), "http://www.w3.org/2003/InkML");

  std::vector<xmlNode*> sources, channels, traces;
  collect(root, "inkSource", &sources);
  collect(root, "channel", &channels);
  collect(root, "trace", &traces);
  ASSERT_EQ(sources.size(), 1u);
  EXPECT_EQ(attr(sources[0], "model"), std::string(trace_.device->name));
  const std::vector<std::pair<std::string, std::string>> expected = {
      {"X", "mm"}, {"Y", "mm"}, {"F", "dev"}, {"OTx", "deg"}, {"OTy", "deg"}, {"T", "ms"}};
  ASSERT_EQ(channels.size(), expected.size());
  for (size_t c = 0; c < channels.size(); ++c) {
    EXPECT_EQ(attr(channels[c], "name"), expected[c].first);
    EXPECT_EQ(attr(channels[c], "units"), expected[c].second);
  }
  EXPECT_EQ(attr(channels[2], "max"), std::to_string(trace_.device->pressure_max));

  // Every sample, in order, from the traces.
  size_t i = 0;
  size_t pen_down_traces = 0;
  for (xmlNode* trace : traces) {
    xmlChar* content = xmlNodeGetContent(trace);
    const std::string points = reinterpret_cast<const char*>(content);
    xmlFree(content);
    const bool down = attr(trace, "type") == "penDown";
    if (down) ++pen_down_traces;
    for (const std::string& point : split(points, ',')) {
      std::vector<std::string> v;
      for (const std::string& p : split(point, ' '))
        if (!p.empty()) v.push_back(p);
      ASSERT_EQ(v.size(), 6u) << point;
      ASSERT_LT(i, samples_.size());
      const PenSample& s = samples_[i];
      EXPECT_EQ(down, s.tipDown()) << i;
      EXPECT_EQ(toDouble(v[0]), s.x_mm) << i;
      EXPECT_EQ(toDouble(v[1]), s.y_mm) << i;
      EXPECT_EQ(std::stoi(v[2]), s.pressure_raw) << i;
      EXPECT_EQ(toFloat(v[3]), s.tilt_x_deg) << i;
      EXPECT_EQ(toFloat(v[4]), s.tilt_y_deg) << i;
      EXPECT_EQ(exactDecimal(v[5], 6), s.t_ns - trace_.t0_ns) << i;
      ++i;
    }
  }
  EXPECT_EQ(i, samples_.size());
  EXPECT_EQ(pen_down_traces, measureStrokes(trace_).size());
  xmlFreeDoc(doc);
}

TEST_F(TraceExport, SamplesCsvRoundTripsToTheJournal) {
  std::ostringstream out;
  writeSamplesCsv(out, {trace_});
  std::istringstream in(out.str());
  std::string line;
  ASSERT_TRUE(std::getline(in, line));
  std::vector<std::string> header;
  ASSERT_TRUE(splitCsvLine(line, &header));
  const auto col = [&](const std::string& name) {
    for (size_t c = 0; c < header.size(); ++c)
      if (header[c] == name) return c;
    ADD_FAILURE() << "no column " << name;
    return size_t(0);
  };
  size_t i = 0;
  std::vector<std::string> f;
  while (std::getline(in, line)) {
    ASSERT_TRUE(splitCsvLine(line, &f));
    ASSERT_EQ(f.size(), header.size());
    ASSERT_LT(i, samples_.size());
    PenSample s;
    s.t_ns = std::stoll(f[col("t_ns")]);
    s.x_raw = std::stoi(f[col("x_raw")]);
    s.y_raw = std::stoi(f[col("y_raw")]);
    s.x_mm = toDouble(f[col("x_mm")]);
    s.y_mm = toDouble(f[col("y_mm")]);
    s.pressure_raw = std::stoi(f[col("pressure_raw")]);
    s.pressure = toFloat(f[col("pressure")]);
    s.tilt_x_raw = std::stoi(f[col("tilt_x_raw")]);
    s.tilt_y_raw = std::stoi(f[col("tilt_y_raw")]);
    s.tilt_x_deg = toFloat(f[col("tilt_x_deg")]);
    s.tilt_y_deg = toFloat(f[col("tilt_y_deg")]);
    s.distance_raw = std::stoi(f[col("distance_raw")]);
    s.distance = toFloat(f[col("distance")]);
    s.buttons = uint32_t(std::stoul(f[col("buttons")]));
    const std::string tool = f[col("tool")];
    s.tool = tool == "pen" ? PenTool::kPen : tool == "eraser" ? PenTool::kEraser : PenTool::kNone;
    s.tool_id = uint32_t(std::stoul(f[col("tool_id")]));
    s.tool_serial = std::stoull(f[col("tool_serial")]);
    s.in_proximity = f[col("in_proximity")] == "1";
    EXPECT_TRUE(samePenState(s, samples_[i])) << "sample " << i;
    EXPECT_EQ(s.t_ns, samples_[i].t_ns);
    EXPECT_EQ(exactDecimal(f[col("t_s")], 9), samples_[i].t_ns - trace_.t0_ns);
    EXPECT_EQ(f[col("tip")], samples_[i].tipDown() ? "1" : "0");
    EXPECT_EQ(f[col("stroke")] == "NA", !samples_[i].tipDown()) << i;
    ++i;
  }
  EXPECT_EQ(i, samples_.size());
}

TEST_F(TraceExport, StrokesFollowTipRunsAndTheBrushInForce) {
  const std::vector<StrokeMeasures> strokes = measureStrokes(trace_);
  ASSERT_EQ(strokes.size(), 2u);
  EXPECT_EQ(strokes[0].brush, "3d");
  EXPECT_EQ(strokes[1].brush, "2d");
  EXPECT_EQ(strokes[0].mode, "paint");
  for (const StrokeMeasures& m : strokes) {
    // Independent recomputation of the path length, duration and pressures.
    double length = 0, max_p = 0, sum_p = 0;
    for (size_t k = m.first_sample; k < m.first_sample + m.sample_count; ++k) {
      const PenSample& s = samples_[k];
      ASSERT_TRUE(s.tipDown());
      if (k > m.first_sample)
        length += std::hypot(s.x_mm - samples_[k - 1].x_mm, s.y_mm - samples_[k - 1].y_mm);
      max_p = std::max(max_p, double(s.pressure));
      sum_p += s.pressure;
    }
    EXPECT_GT(length, 1.0);
    EXPECT_NEAR(m.path_length_mm, length, 1e-9);
    EXPECT_EQ(m.max_pressure, max_p);
    EXPECT_NEAR(m.mean_pressure, sum_p / double(m.sample_count), 1e-12);
    const double duration =
        double(samples_[m.first_sample + m.sample_count - 1].t_ns - samples_[m.first_sample].t_ns) *
        1e-9;
    EXPECT_NEAR(m.duration_s, duration, 1e-12);
    ASSERT_TRUE(m.speed_mm_s.has_value());
    EXPECT_NEAR(*m.speed_mm_s, length / duration, 1e-9);
    EXPECT_FALSE(m.mapping_ms.has_value());  // not journalled yet
  }
  std::ostringstream out;
  writeStrokesCsv(out, {trace_});
  const std::vector<std::string> lines = split(out.str(), '\n');
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_NE(lines[1].find(",3d,paint,NA"), std::string::npos) << lines[1];
  EXPECT_NE(lines[2].find(",2d,paint,NA"), std::string::npos) << lines[2];
}

TEST_F(TraceExport, EventsListEveryChangeAndMarker) {
  std::ostringstream out;
  writeEventsCsv(out, {trace_});
  std::istringstream in(out.str());
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "participant,session,t_s,record,kind,key,value,task");
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> f;
  // The session record's value spans lines (RFC 4180 quoting); join until quotes balance.
  std::string record;
  while (std::getline(in, line)) {
    record += record.empty() ? line : "\n" + line;
    if (std::count(record.begin(), record.end(), '"') % 2 != 0) continue;
    std::vector<std::string> fields;
    std::string field;
    bool quoted = false;
    for (size_t i = 0; i < record.size(); ++i) {
      const char c = record[i];
      if (quoted && c == '"' && i + 1 < record.size() && record[i + 1] == '"') {
        field += '"';
        ++i;
      } else if (c == '"') {
        quoted = !quoted;
      } else if (c == ',' && !quoted) {
        fields.push_back(field);
        field.clear();
      } else {
        field += c;
      }
    }
    fields.push_back(field);
    rows.push_back(fields);
    record.clear();
  }
  ASSERT_EQ(rows.size(), trace_.events.size());
  for (const auto& row : rows) ASSERT_EQ(row.size(), 8u);
  EXPECT_EQ(rows[0][4], "device");
  EXPECT_EQ(rows[1][4], "session");
  EXPECT_EQ(rows[1][6], "format = 2\ngrid = 64\n");
  EXPECT_EQ(rows[2][4], "mode");
  EXPECT_EQ(rows[2][5], "mode");
  EXPECT_EQ(rows[2][6], "paint");
  EXPECT_EQ(rows[2][2], "0.000001000");
  EXPECT_EQ(rows[3][5], "brush");
  EXPECT_EQ(rows[3][6], "3d");
  EXPECT_EQ(rows[5][4], "marker");
  EXPECT_EQ(rows[5][6], "task 1, stroke boundary, \"quoted\"");
  EXPECT_EQ(rows[6][5], "undo");
  EXPECT_EQ(rows[6][6], "NA");
}

TEST_F(TraceExport, ManySessionsGoIntoOneFilePerKind) {
  const std::string second_path = tempPath("b.cbj");
  const std::vector<PenSample> second = writeJournal(second_path, 9'000'000'000);
  const SessionTrace b = loadSessionTrace(second_path);
  std::filesystem::remove(second_path);
  std::ostringstream samples, strokes, ink;
  writeSamplesCsv(samples, {trace_, b});
  writeStrokesCsv(strokes, {trace_, b});
  writeInkml(ink, {trace_, b});
  const std::vector<std::string> sample_lines = split(samples.str(), '\n');
  EXPECT_EQ(sample_lines.size(), 1 + samples_.size() + second.size());
  // Not a study session: no participant (NA), the session is the journal's name.
  EXPECT_EQ(sample_lines[1].rfind("NA," + trace_.id + ",0,", 0), 0u) << sample_lines[1];
  EXPECT_EQ(sample_lines[1 + samples_.size()].rfind("NA," + b.id + ",0,", 0), 0u);
  EXPECT_EQ(split(strokes.str(), '\n').size(), 5u);
  xmlDoc* doc =
      xmlReadMemory(ink.str().data(), int(ink.str().size()), "t.inkml", nullptr, XML_PARSE_NONET);
  ASSERT_NE(doc, nullptr);
  std::vector<xmlNode*> contexts, groups;
  collect(xmlDocGetRootElement(doc), "context", &contexts);
  collect(xmlDocGetRootElement(doc), "traceGroup", &groups);
  ASSERT_EQ(contexts.size(), 2u);
  ASSERT_EQ(groups.size(), 2u);
  EXPECT_EQ(attr(groups[1], "contextRef"), "#" + attr(contexts[1], "id"));
  xmlFreeDoc(doc);
}

TEST(TraceExportErrors, TruncatedJournalKeepsItsIntactPrefix) {
  const std::string path = tempPath("torn.cbj");
  const std::vector<PenSample> samples = writeJournal(path, 0);
  const auto size = std::filesystem::file_size(path);
  std::filesystem::resize_file(path, size - 30);
  const SessionTrace trace = loadSessionTrace(path);
  EXPECT_FALSE(trace.journal_warning.empty());
  EXPECT_NE(trace.journal_warning.find(path), std::string::npos) << trace.journal_warning;
  ASSERT_GT(trace.samples.size(), 10u);
  EXPECT_LE(trace.samples.size(), samples.size());
  EXPECT_TRUE(samePenState(trace.samples.back(), samples[trace.samples.size() - 1]));
  std::filesystem::remove(path);
}

TEST(TraceExportErrors, MalformedSampleAndMissingFileNameTheFile) {
  const std::string path = tempPath("bad.cbj");
  {
    JournalWriter journal;
    ASSERT_TRUE(journal.open(path));
    const uint8_t three[3] = {1, 2, 3};
    journal.append(JournalRecordType::kMode, 0, "paint");
    journal.append(JournalRecordType::kPenSample, 1, three, 3);
  }
  try {
    loadSessionTrace(path);
    FAIL() << "a 3-byte pen sample was accepted";
  } catch (const StudyInputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path), std::string::npos) << what;
    EXPECT_NE(what.find("record 1"), std::string::npos) << what;
  }
  std::filesystem::remove(path);
  EXPECT_THROW(loadSessionTrace(tempPath("missing.cbj")), StudyInputError);
}

TEST(TraceExportErrors, Utf8IsRepairedOnlyWhereBroken) {
  const std::string good = "\xE4\xBA\x91 cloud \xC3\xBC \xE2\x82\xAC \xF0\x9F\x96\x8C";
  EXPECT_EQ(validUtf8(good), good);
  const std::string fffd = "\xEF\xBF\xBD";
  EXPECT_EQ(validUtf8("a\xFF"
                      "b"),
            "a" + fffd + "b");
  EXPECT_EQ(validUtf8("\xC0\xAF"), fffd + fffd);                // overlong '/'
  EXPECT_EQ(validUtf8("\xED\xA0\x80"), fffd + fffd + fffd);     // a surrogate
  EXPECT_EQ(validUtf8("\xF4\x90\x80\x80").substr(0, 3), fffd);  // above U+10FFFF
  EXPECT_EQ(validUtf8("ok\xE4\xBA"), "ok" + fffd + fffd);       // cut short at the end
}

// A journal from elsewhere: a device name that is not UTF-8 and has markup and a control
// character; samples with NaN and infinite values.
TEST(TraceExportErrors, ForeignBytesStillGiveWellFormedInkmlAndReadableCsv) {
  const std::string path = tempPath("foreign.cbj");
  {
    JournalWriter journal;
    ASSERT_TRUE(journal.open(path));
    PenDeviceInfo device;
    std::snprintf(device.name, sizeof device.name, "<pen & \"tablet\"\x01\xFF\xFE>");
    device.pressure_max = 1023;
    const std::vector<uint8_t> payload = encodeDeviceInfo(device);
    journal.append(JournalRecordType::kDevice, 0, payload.data(), payload.size());
    journal.append(JournalRecordType::kMarker, 0, "note \xFF");
    PenSample s;
    s.t_ns = 1;
    s.buttons = kPenTip;
    s.x_mm = std::nan("");
    s.y_mm = INFINITY;
    s.tilt_x_deg = -INFINITY;
    ASSERT_TRUE(journal.appendPenSample(s));
  }
  const SessionTrace trace = loadSessionTrace(path);
  std::filesystem::remove(path);
  std::ostringstream ink, samples, events;
  writeInkml(ink, {trace});
  writeSamplesCsv(samples, {trace});
  writeEventsCsv(events, {trace});
  xmlDoc* doc = xmlReadMemory(ink.str().data(), int(ink.str().size()), "foreign.inkml", nullptr,
                              XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING);
  ASSERT_NE(doc, nullptr) << ink.str();
  std::vector<xmlNode*> sources;
  collect(xmlDocGetRootElement(doc), "inkSource", &sources);
  ASSERT_EQ(sources.size(), 1u);
  EXPECT_EQ(attr(sources[0], "model"), "<pen & \"tablet\"?\xEF\xBF\xBD\xEF\xBF\xBD>");
  xmlFreeDoc(doc);
  const std::vector<std::string> lines = split(samples.str(), '\n');
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_NE(lines[1].find(",NaN,Inf,"), std::string::npos) << lines[1];
  EXPECT_NE(lines[1].find(",-Inf,"), std::string::npos) << lines[1];
  EXPECT_NE(events.str().find("note \xEF\xBF\xBD"), std::string::npos);
}

}  // namespace
}  // namespace cb

namespace cb {
namespace {

// Two study sessions' journals are both `session.cbj`: each is named by its folder, carries its
// participant in every row, and its rows say which task they were written in.
TEST(TraceExportStudy, SessionsAreNamedByFolderWithParticipantAndTaskInEveryRow) {
  std::vector<SessionTrace> traces;
  for (const std::string participant : {"P01", "P02"}) {
    const std::filesystem::path dir =
        std::filesystem::path(tempPath("study")) / (participant + std::string("-20261129T010000Z"));
    std::filesystem::create_directories(dir);
    const std::string path = (dir / "session.cbj").string();
    {
      JournalWriter journal;
      ASSERT_TRUE(journal.open(path)) << journal.error();
      journal.append(JournalRecordType::kSession, 0, "format = 2\ngrid = 64\n");
      journal.append(JournalRecordType::kMarker, 0,
                     "study.info protocol=thesis participant=" + participant + " number=1");
      PenSample s;
      s.t_ns = 10, s.buttons = kPenTip, s.in_proximity = true;
      journal.appendPenSample(s);  // free drawing: no task
      journal.append(JournalRecordType::kMarker, 20,
                     "study.stage-begin stage=task task=cloud1 position=1 limit_s=600");
      s.t_ns = 30;
      journal.appendPenSample(s);
      journal.append(JournalRecordType::kMarker, 40,
                     "study.stage-end stage=task task=cloud1 "
                     "position=1 how=done");
    }
    EXPECT_EQ(sessionIdForJournal(path), participant + std::string("-20261129T010000Z"));
    traces.push_back(loadSessionTrace(path));
    EXPECT_EQ(traces.back().participant, participant);
  }
  EXPECT_NE(traces[0].id, traces[1].id);
  std::ostringstream samples, strokes, events;
  writeSamplesCsv(samples, traces);
  writeStrokesCsv(strokes, traces);
  writeEventsCsv(events, traces);
  const std::vector<std::string> rows = split(samples.str(), '\n');
  ASSERT_EQ(rows.size(), 5u);  // header and two samples per session
  EXPECT_EQ(rows[0].substr(0, 27), "participant,session,sample,");
  EXPECT_EQ(rows[1].substr(0, 24), "P01,P01-20261129T010000Z");
  EXPECT_EQ(rows[1].substr(rows[1].rfind(',')), ",NA");      // free drawing
  EXPECT_EQ(rows[2].substr(rows[2].rfind(',')), ",cloud1");  // in the task
  EXPECT_EQ(rows[4].substr(0, 24), "P02,P02-20261129T010000Z");
  EXPECT_NE(strokes.str().find("\nP02,P02-20261129T010000Z,"), std::string::npos);
  EXPECT_NE(events.str().find("study.stage-end"), std::string::npos);
}

}  // namespace
}  // namespace cb

namespace cb {
namespace {

// One row per task from the runner's markers: onset on both clocks, duration on the stage
// clock (the closing marker's seconds, not end − begin), the end reason and the counts.
TEST(TraceExportStudy, TrialsHaveOneRowPerTaskWithStageClockDurationAndEndReason) {
  const std::string path = tempPath("trials.cbj");
  {
    JournalWriter j;
    ASSERT_TRUE(j.open(path)) << j.error();
    j.append(JournalRecordType::kSession, 1'000, "format = 2\ngrid = 64\n");
    j.append(JournalRecordType::kMarker, 1'000,
             "study.info participant=P07 number=7 monotonic_ns=1000 "
             "wall_clock_unix_ns=1800000000000000000");
    j.append(JournalRecordType::kMarker, 5'000'000'000,
             "study.stage-begin stage=task task=cloud3 position=1 limit_s=90");
    j.append(JournalRecordType::kMode, 5'000'000'001, "paint");
    j.append(JournalRecordType::kStrokeMapped, 6'000'000'000, "stroke = 0\nmapping_ms = 4\n");
    j.append(JournalRecordType::kStrokeMapped, 7'000'000'000, "stroke = 1\nmapping_ms = 4\n");
    j.append(JournalRecordType::kUi, 8'000'000'000, "undo");
    j.append(JournalRecordType::kMode, 9'000'000'000, "erase");
    j.append(JournalRecordType::kStrokeMapped, 9'500'000'000, "stroke = 2\nmapping_ms = 4\n");
    // 109 s after the onset on the monotonic clock, 90 s on the stage clock (a pause).
    j.append(JournalRecordType::kMarker, 114'000'000'000,
             "study.stage-closing stage=task task=cloud3 position=1 why=\"time up\" seconds=90");
    j.append(JournalRecordType::kMarker, 115'000'000'000,
             "study.stage-end stage=task task=cloud3 position=1 how=\"time up\"");
    j.append(JournalRecordType::kMarker, 116'000'000'000,
             "study.stage-begin stage=task task=cloud1 position=2 limit_s=90");
    j.append(JournalRecordType::kMarker, 120'000'000'000,
             "study.stage-closing stage=task task=cloud1 position=2 why=\"skipped: participant "
             "left\" seconds=4");
    j.append(JournalRecordType::kStrokeMapped, 120'500'000'000, "stroke = 3\nmapping_ms = 4\n");
  }
  const SessionTrace trace = loadSessionTrace(path);
  const std::vector<TrialRow> trials = trialsOfSession(trace);
  ASSERT_EQ(trials.size(), 2u);
  EXPECT_EQ(trials[0].task, "cloud3");
  EXPECT_EQ(trials[0].order, 1);
  EXPECT_EQ(trials[0].onset_ns, 5'000'000'000);
  ASSERT_TRUE(trials[0].onset_unix_ns.has_value());
  EXPECT_EQ(*trials[0].onset_unix_ns, 1'800'000'000'000'000'000 + 5'000'000'000 - 1'000);
  ASSERT_TRUE(trials[0].duration_s.has_value());
  EXPECT_EQ(*trials[0].duration_s, 90.0);
  EXPECT_EQ(trials[0].end_reason, "time-up");
  EXPECT_EQ(trials[0].strokes, 2);
  EXPECT_EQ(trials[0].erases, 1);
  EXPECT_EQ(trials[0].undos, 1);
  EXPECT_EQ(trials[1].end_reason, "skipped");
  EXPECT_EQ(trials[1].erases, 1);  // the stroke after closing, before the stage's end, counts
  std::ostringstream csv;
  writeTrialsCsvHeader(csv);
  writeTrialsCsvRows(csv, trace);
  const std::vector<std::string> lines = split(csv.str(), '\n');
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[1], "P07," + trace.id +
                          ",cloud3,1,4.999999000,5000000000,1800000004999999000,90,time-up,2,1,1");
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace cb

namespace cb {
namespace {

// strokes.csv's rows as the painter saw the pen: its strokes (by the journal's stroke_begin
// sync markers, numbered as the painter numbered them), a tip-down run it cut into two strokes,
// an erase drag, and a tap on the on-screen UI (pen_capture=on), each a row of its own kind.
TEST(TraceExportGestures, RowsFollowThePaintersStrokesAndMarkErasesAndMenuTaps) {
  const std::string path = tempPath("gestures.cbj");
  int64_t t = 1'000'000'000;
  size_t samples = 0;
  {
    JournalWriter j;
    ASSERT_TRUE(j.open(path)) << j.error();
    j.append(JournalRecordType::kSession, t, "format = 2\ngrid = 64\n");
    j.append(JournalRecordType::kMode, t, "paint");
    const auto sample = [&](bool tip, float x) {
      PenSample s;
      s.t_ns = (t += 5'000'000);
      s.buttons = tip ? kPenTip : 0u;
      s.in_proximity = true;
      s.x_mm = x;
      s.pressure = tip ? 0.5f : 0.0f;
      j.appendPenSample(s);
      ++samples;
    };
    const auto sync = [&](const char* kind, int index) {
      SyncMarker m;
      m.seq = 1, m.kind = kind, m.mono_ns = t, m.label = std::to_string(index);
      j.append(JournalRecordType::kSync, t, formatSyncMarker(m));
    };
    // Samples 0-3: a run whose first raw sample precedes the painter's contact (stroke 4: the
    // painter's numbers, not the rows').
    sample(true, 0), sample(true, 1), sync("stroke_begin", 4), sample(true, 2), sample(false, 3);
    sync("stroke_end", 4);
    j.append(JournalRecordType::kStrokeMapped, t, "stroke = 4\nmapping_ms = 7.5\n");
    // Samples 4-8: one run the painter cut in two (pressure fell below contact and rose again).
    sample(true, 4), sync("stroke_begin", 5), sample(true, 5), sync("stroke_end", 5);
    sample(true, 6), sync("stroke_begin", 6), sample(true, 7), sample(false, 8);
    sync("stroke_end", 6);
    // Samples 9-11: an erase drag.
    j.append(JournalRecordType::kUi, t, "mode=erase");
    j.append(JournalRecordType::kMode, t, "erase");
    sample(true, 9), sample(true, 10), sample(false, 11);
    // Samples 12-13: a tap on the menu.
    j.append(JournalRecordType::kUi, t, "pen_capture=on");
    sample(true, 12), sample(false, 13);
    j.append(JournalRecordType::kUi, t, "pen_capture=off");
  }
  const SessionTrace trace = loadSessionTrace(path);
  ASSERT_EQ(trace.samples.size(), samples);
  const std::vector<StrokeMeasures> rows = measureStrokes(trace);
  ASSERT_EQ(rows.size(), 5u);
  const auto expectRow = [&](size_t i, const char* kind, std::optional<uint32_t> stroke,
                             size_t first, size_t count) {
    SCOPED_TRACE("row " + std::to_string(i));
    EXPECT_EQ(rows[i].index, i);
    EXPECT_EQ(rows[i].kind, kind);
    EXPECT_EQ(rows[i].stroke, stroke);
    EXPECT_EQ(rows[i].first_sample, first);
    EXPECT_EQ(rows[i].sample_count, count);
  };
  expectRow(0, "stroke", 4, 0, 3);
  expectRow(1, "stroke", 5, 4, 2);
  expectRow(2, "stroke", 6, 6, 2);
  expectRow(3, "erase", std::nullopt, 9, 2);
  expectRow(4, "menu_tap", std::nullopt, 12, 1);
  ASSERT_TRUE(rows[0].mapping_ms.has_value());
  EXPECT_EQ(*rows[0].mapping_ms, 7.5);
  EXPECT_FALSE(rows[1].mapping_ms.has_value()) << "stroke 5 has no StrokeMapped record";
  EXPECT_EQ(rows[3].mode, "erase");

  std::ostringstream csv;
  writeStrokesCsv(csv, {trace});
  const std::vector<std::string> lines = split(csv.str(), '\n');
  ASSERT_EQ(lines.size(), 6u);
  const auto startsWith = [](const std::string& line, const std::string& prefix) {
    return line.rfind(prefix, 0) == 0;
  };
  EXPECT_TRUE(startsWith(lines[0], "participant,session,gesture,kind,stroke,")) << lines[0];
  EXPECT_TRUE(startsWith(lines[1], "NA," + trace.id + ",0,stroke,4,")) << lines[1];
  EXPECT_TRUE(startsWith(lines[4], "NA," + trace.id + ",3,erase,NA,")) << lines[4];
  EXPECT_TRUE(startsWith(lines[5], "NA," + trace.id + ",4,menu_tap,NA,")) << lines[5];
  std::ostringstream samples_csv;
  writeSamplesCsv(samples_csv, {trace});
  const std::vector<std::string> sample_lines = split(samples_csv.str(), '\n');
  // Sample 5 is in the second row (gesture 1), the painter's stroke 5; sample 10 is erasing.
  EXPECT_NE(sample_lines[1 + 5].find(",1,5,NA"), std::string::npos) << sample_lines[6];
  EXPECT_NE(sample_lines[1 + 10].find(",3,NA,NA"), std::string::npos) << sample_lines[11];
  EXPECT_NE(sample_lines[1 + 8].find(",NA,NA,NA"), std::string::npos) << sample_lines[9];
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace cb
