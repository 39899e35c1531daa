#include "app/study/study_report_html.h"

#include <algorithm>
#include <cstdio>

#include "app/study/svg_charts.h"

namespace cb {
namespace {

std::string fixed(double v, int digits) {
  char text[40];
  std::snprintf(text, sizeof text, "%.*f", digits, v);
  return text;
}

std::string sdText(const std::optional<double>& sd) {
  return sd ? fixed(*sd, 2) : "–";
}

std::string itemTable(const StudyReport& report, int scale_min) {
  std::string html = "<table><tr><th>item</th><th>n</th>";
  const size_t points = report.items.empty() ? 0 : report.items.front().counts.size();
  for (size_t k = 0; k < points; ++k) html += "<th>" + std::to_string(scale_min + int(k)) + "</th>";
  html += "<th>mean</th><th>SD</th></tr>\n";
  for (const ItemSummary& item : report.items) {
    html += "<tr><td>" + htmlEscape(item.item) + "</td><td>" + std::to_string(item.n) + "</td>";
    for (size_t count : item.counts) html += "<td>" + std::to_string(count) + "</td>";
    html += "<td>" + fixed(item.mean, 2) + "</td><td>" + sdText(item.sd) + "</td></tr>\n";
  }
  return html + "</table>\n";
}

std::string constructTable(const StudyReport& report) {
  std::string html =
      "<table><tr><th>construct</th><th>items</th><th>participants</th><th>mean</th><th>SD</th>"
      "</tr>\n";
  for (const ConstructSummary& c : report.constructs) {
    std::string items;
    for (const std::string& id : c.definition.items) items += (items.empty() ? "" : " ") + id;
    html += "<tr><td>" + htmlEscape(c.definition.name) + "</td><td>" + htmlEscape(items) +
            "</td><td>" + std::to_string(c.participants) + "</td><td>" + fixed(c.mean, 2) +
            "</td><td>" + sdText(c.sd) + "</td></tr>\n";
  }
  return html + "</table>\n";
}

std::string pairedSection(const StudyReport& report, const StudyReportOptions& options) {
  std::string html = "<h2>Paired comparison: " + htmlEscape(options.paired_first) + " vs " +
                     htmlEscape(options.paired_second) + "</h2>\n";
  if (!report.paired)
    return html + "<p class=\"problem\">" + htmlEscape(report.paired_problem) + "</p>\n";
  const PairedTTest& t = *report.paired;
  html += "<p>Paired t-test over the " + std::to_string(t.n) +
          " participants who answered both (Student 1908; as in the thesis §7.7.2, where Q3 "
          "rates the 2D brush and Q6 the 3D brush). Alternative: " +
          htmlEscape(t.second) + " is rated higher than " + htmlEscape(t.first) + ".</p>\n";
  html += "<table><tr><th>" + htmlEscape(t.first) + " mean</th><th>" + htmlEscape(t.second) +
          " mean</th><th>mean difference</th><th>SD of differences</th><th>t</th><th>df</th>"
          "<th>p (one-tailed)</th><th>p (two-tailed)</th></tr>\n<tr><td>" +
          fixed(t.mean_first, 2) + "</td><td>" + fixed(t.mean_second, 2) + "</td><td>" +
          fixed(t.mean_difference, 3) + "</td><td>" + fixed(t.sd_difference, 3) + "</td><td>" +
          fixed(t.t, 3) + "</td><td>" + fixed(t.degrees_of_freedom, 0) + "</td><td>" +
          fixed(t.p_one_tailed, 3) + "</td><td>" + fixed(t.p_two_tailed, 3) +
          "</td></tr></table>\n";
  return html;
}

std::string sessionSection(const StudyReport& report) {
  if (report.sessions.empty()) return "";
  std::string html =
      "<h2>Sessions</h2>\n<table><tr><th>session</th><th>duration (s)</th><th>samples</th>"
      "<th>strokes</th><th>tip down (s)</th></tr>\n";
  for (const SessionFigures& s : report.sessions)
    html += "<tr><td>" + htmlEscape(s.id) + "</td><td>" + fixed(s.duration_s, 1) + "</td><td>" +
            std::to_string(s.samples) + "</td><td>" + std::to_string(s.strokes) + "</td><td>" +
            fixed(s.tip_down_s, 1) + "</td></tr>\n";
  html += "</table>\n";
  for (const SessionFigures& s : report.sessions) {
    html += "<h3>" + htmlEscape(s.id) + "</h3>\n";
    // Pen sample -> present latency, frame intervals and missed refreshes (Frame records).
    html += "<pre>" + htmlEscape(formatFrameTimingStats(s.timing, "")) + "</pre>\n";
    html +=
        timeSeriesSvg(s.pressure_t, s.pressure, "pressure while the tip is down", "0..1", 0.0, 1.0);
    const double top_speed = s.stroke_speed.empty()
                                 ? 1.0
                                 : *std::max_element(s.stroke_speed.begin(), s.stroke_speed.end());
    html += timeSeriesSvg(s.stroke_start_s, s.stroke_speed, "mean speed per stroke", "mm/s", 0.0,
                          top_speed);
  }
  return html;
}

}  // namespace

std::string studyReportHtml(const StudyReport& report, const StudyReportOptions& options,
                            int scale_min, int scale_max) {
  std::string html =
      "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>" +
      htmlEscape(options.title) +
      "</title>\n<style>body{font-family:sans-serif;max-width:60em;margin:1em auto;padding:0 1em}"
      "table{border-collapse:collapse;margin:.5em 0}td,th{border:1px solid #ccc;padding:2px 6px;"
      "text-align:right}td:first-child,th:first-child{text-align:left}.problem{color:#a00}"
      "</style></head><body>\n";
  html += "<h1>" + htmlEscape(options.title) + "</h1>\n";
  html +=
      "<p>Answers: " + htmlEscape(options.answers_name) + " — " +
      std::to_string(report.participants) + " participants, " +
      std::to_string(report.items.size()) + " items on a " + std::to_string(scale_min) + ".." +
      std::to_string(scale_max) +
      " scale. Means and sample standard deviations (n − 1); missing answers are left out.</p>\n";
  html += "<h2>Answers per item</h2>\n" + likertStackedBarsSvg(report.items, scale_min) +
          itemTable(report, scale_min);
  if (!report.constructs.empty()) {
    html += "<h2>Constructs</h2>\n<p>";
    if (!options.constructs_source.empty()) html += htmlEscape(options.constructs_source) + ". ";
    html +=
        "Each participant's score is the mean of the construct's items they answered; the "
        "table gives the mean and SD of those scores.</p>\n" +
        constructMeansSvg(report.constructs, scale_min, scale_max) + constructTable(report);
  }
  html += pairedSection(report, options);
  html += sessionSection(report);
  return html + "</body></html>\n";
}

}  // namespace cb
