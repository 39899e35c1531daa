#include "app/study/svg_charts.h"

#include <algorithm>
#include <cstdio>

#include "app/study/utf8_text.h"

namespace cb {
namespace {

std::string num(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", v);
  return text;
}

// Five diverging colours (ColorBrewer RdBu, colorblind-safe), from disagree to agree; scales
// with more points reuse the ends.
const char* scaleColour(size_t k, size_t points) {
  static const char* kColours[] = {"#ca0020", "#f4a582", "#d9d9d9", "#92c5de", "#0571b0"};
  if (points <= 1) return kColours[2];
  const size_t index = (k * 4 + (points - 1) / 2) / (points - 1);
  return kColours[std::min<size_t>(index, 4)];
}

}  // namespace

std::string htmlEscape(const std::string& raw) {
  return markupEscape(raw);
}

std::string likertStackedBarsSvg(const std::vector<ItemSummary>& items, int scale_min) {
  const double label_w = 60, bar_w = 420, right_w = 130, row_h = 20, top = 28;
  const double width = label_w + bar_w + right_w;
  const double height = top + row_h * double(items.size()) + 8;
  std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + num(width) +
                    "\" height=\"" + num(height) +
                    "\" role=\"img\" font-family=\"sans-serif\" "
                    "font-size=\"12\"><title>Answers per item, share of each scale point</title>\n";
  const size_t points = items.empty() ? 0 : items.front().counts.size();
  for (size_t k = 0; k < points; ++k) {
    const double x = label_w + bar_w * double(k) / double(points);
    svg += "<rect x=\"" + num(x) + "\" y=\"4\" width=\"12\" height=\"12\" fill=\"" +
           scaleColour(k, points) + "\"/><text x=\"" + num(x + 16) + "\" y=\"14\">" +
           std::to_string(scale_min + int(k)) + "</text>\n";
  }
  for (size_t r = 0; r < items.size(); ++r) {
    const ItemSummary& item = items[r];
    const double y = top + row_h * double(r);
    svg += "<text x=\"0\" y=\"" + num(y + 14) + "\">" + htmlEscape(item.item) + "</text>\n";
    double x = label_w;
    for (size_t k = 0; k < item.counts.size() && item.n > 0; ++k) {
      const double w = bar_w * double(item.counts[k]) / double(item.n);
      if (w <= 0) continue;
      svg += "<rect x=\"" + num(x) + "\" y=\"" + num(y + 2) + "\" width=\"" + num(w) +
             "\" height=\"" + num(row_h - 4) + "\" fill=\"" + scaleColour(k, item.counts.size()) +
             "\"><title>" + htmlEscape(item.item) + ": " + std::to_string(item.counts[k]) +
             " answered " + std::to_string(scale_min + int(k)) + "</title></rect>\n";
      x += w;
    }
    svg += "<text x=\"" + num(label_w + bar_w + 8) + "\" y=\"" + num(y + 14) +
           "\">n=" + std::to_string(item.n) + " mean " + num(item.mean) + "</text>\n";
  }
  return svg + "</svg>\n";
}

std::string constructMeansSvg(const std::vector<ConstructSummary>& constructs, int scale_min,
                              int scale_max) {
  const double label_w = 140, axis_w = 400, row_h = 26, top = 10, bottom = 26;
  const double width = label_w + axis_w + 20;
  const double height = top + row_h * double(constructs.size()) + bottom;
  const auto xOf = [&](double v) {
    return label_w + axis_w * (v - scale_min) / double(std::max(1, scale_max - scale_min));
  };
  std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + num(width) +
                    "\" height=\"" + num(height) +
                    "\" role=\"img\" font-family=\"sans-serif\" "
                    "font-size=\"12\"><title>Construct means with ±1 SD</title>\n";
  const double axis_y = top + row_h * double(constructs.size());
  for (int v = scale_min; v <= scale_max; ++v) {
    svg += "<line x1=\"" + num(xOf(v)) + "\" y1=\"" + num(top) + "\" x2=\"" + num(xOf(v)) +
           "\" y2=\"" + num(axis_y) + "\" stroke=\"#ddd\"/><text x=\"" + num(xOf(v) - 3) +
           "\" y=\"" + num(axis_y + 16) + "\">" + std::to_string(v) + "</text>\n";
  }
  for (size_t r = 0; r < constructs.size(); ++r) {
    const ConstructSummary& c = constructs[r];
    const double y = top + row_h * double(r) + row_h / 2;
    svg += "<text x=\"0\" y=\"" + num(y + 4) + "\">" + htmlEscape(c.definition.name) + "</text>\n";
    if (c.sd) {
      const double lo = std::max<double>(scale_min, c.mean - *c.sd);
      const double hi = std::min<double>(scale_max, c.mean + *c.sd);
      svg += "<line x1=\"" + num(xOf(lo)) + "\" y1=\"" + num(y) + "\" x2=\"" + num(xOf(hi)) +
             "\" y2=\"" + num(y) + "\" stroke=\"#333\" stroke-width=\"2\"/>\n";
    }
    svg += "<circle cx=\"" + num(xOf(c.mean)) + "\" cy=\"" + num(y) +
           "\" r=\"5\" fill=\"#0571b0\"><title>" + htmlEscape(c.definition.name) + ": mean " +
           num(c.mean) + (c.sd ? ", SD " + num(*c.sd) : std::string()) + "</title></circle>\n";
  }
  return svg + "</svg>\n";
}

std::string timeSeriesSvg(const std::vector<double>& times, const std::vector<double>& values,
                          const std::string& title, const std::string& y_label, double y_min,
                          double y_max) {
  const double left = 50, plot_w = 500, plot_h = 120, top = 18, bottom = 24;
  const double width = left + plot_w + 10, height = top + plot_h + bottom;
  const double t_max =
      times.empty() ? 1.0 : std::max(1e-9, *std::max_element(times.begin(), times.end()));
  const double span = y_max > y_min ? y_max - y_min : 1.0;
  std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + num(width) +
                    "\" height=\"" + num(height) +
                    "\" role=\"img\" font-family=\"sans-serif\" "
                    "font-size=\"11\"><title>" +
                    htmlEscape(title) + "</title>\n";
  svg += "<text x=\"" + num(left) + "\" y=\"12\">" + htmlEscape(title) + "</text>\n";
  svg += "<rect x=\"" + num(left) + "\" y=\"" + num(top) + "\" width=\"" + num(plot_w) +
         "\" height=\"" + num(plot_h) + "\" fill=\"none\" stroke=\"#999\"/>\n";
  svg += "<text x=\"2\" y=\"" + num(top + 10) + "\">" + num(y_max) + "</text><text x=\"2\" y=\"" +
         num(top + plot_h) + "\">" + num(y_min) + "</text><text x=\"2\" y=\"" +
         num(top + plot_h / 2) + "\">" + htmlEscape(y_label) + "</text>\n";
  svg += "<text x=\"" + num(left) + "\" y=\"" + num(height - 6) + "\">0 s</text><text x=\"" +
         num(left + plot_w - 50) + "\" y=\"" + num(height - 6) + "\">" + num(t_max) + " s</text>\n";
  if (!times.empty()) {
    svg += "<polyline fill=\"none\" stroke=\"#0571b0\" stroke-width=\"1\" points=\"";
    const size_t n = std::min(times.size(), values.size());
    for (size_t i = 0; i < n; ++i) {
      const double x = left + plot_w * times[i] / t_max;
      const double v = std::clamp(values[i], y_min, y_max);
      const double y = top + plot_h * (1.0 - (v - y_min) / span);
      svg += num(x) + "," + num(y) + " ";
    }
    svg += "\"/>\n";
  }
  return svg + "</svg>\n";
}

}  // namespace cb
