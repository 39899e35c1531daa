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
           "\">n=" + std::to_string(item.n) +
           (item.mean ? " mean " + num(*item.mean) : std::string(" mean NA")) + "</text>\n";
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
    if (!c.mean) {
      svg += "<text x=\"" + num(label_w + 6) + "\" y=\"" + num(y + 4) +
             "\" fill=\"#a00\">NA: nobody answered its items</text>\n";
      continue;
    }
    const double mean = *c.mean;
    if (c.sd) {
      const double lo = std::max<double>(scale_min, mean - *c.sd);
      const double hi = std::min<double>(scale_max, mean + *c.sd);
      svg += "<line x1=\"" + num(xOf(lo)) + "\" y1=\"" + num(y) + "\" x2=\"" + num(xOf(hi)) +
             "\" y2=\"" + num(y) + "\" stroke=\"#333\" stroke-width=\"2\"/>\n";
    }
    svg += "<circle cx=\"" + num(xOf(mean)) + "\" cy=\"" + num(y) +
           "\" r=\"5\" fill=\"#0571b0\"><title>" + htmlEscape(c.definition.name) + ": mean " +
           num(mean) + (c.sd ? ", SD " + num(*c.sd) : std::string()) + "</title></circle>\n";
  }
  return svg + "</svg>\n";
}

namespace {

struct PlotArea {
  double left = 50, plot_w = 500, plot_h = 120, top = 18, bottom = 24;
  double t_max = 1, y_min = 0, y_max = 1;
  double x(double t) const { return left + plot_w * t / t_max; }
  double y(double v) const {
    const double span = y_max > y_min ? y_max - y_min : 1.0;
    return top + plot_h * (1.0 - (std::clamp(v, y_min, y_max) - y_min) / span);
  }
};

// The opening <svg>, its title, frame and axis labels.
std::string plotFrame(const PlotArea& a, const std::string& title, const std::string& y_label) {
  const double width = a.left + a.plot_w + 10, height = a.top + a.plot_h + a.bottom;
  std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + num(width) +
                    "\" height=\"" + num(height) +
                    "\" role=\"img\" font-family=\"sans-serif\" "
                    "font-size=\"11\"><title>" +
                    htmlEscape(title) + "</title>\n";
  svg += "<text x=\"" + num(a.left) + "\" y=\"12\">" + htmlEscape(title) + "</text>\n";
  svg += "<rect x=\"" + num(a.left) + "\" y=\"" + num(a.top) + "\" width=\"" + num(a.plot_w) +
         "\" height=\"" + num(a.plot_h) + "\" fill=\"none\" stroke=\"#999\"/>\n";
  svg += "<text x=\"2\" y=\"" + num(a.top + 10) + "\">" + num(a.y_max) +
         "</text><text x=\"2\" y=\"" + num(a.top + a.plot_h) + "\">" + num(a.y_min) +
         "</text><text x=\"2\" y=\"" + num(a.top + a.plot_h / 2) + "\">" + htmlEscape(y_label) +
         "</text>\n";
  svg += "<text x=\"" + num(a.left) + "\" y=\"" + num(height - 6) + "\">0 s</text><text x=\"" +
         num(a.left + a.plot_w - 50) + "\" y=\"" + num(height - 6) + "\">" + num(a.t_max) +
         " s</text>\n";
  return svg;
}

double largest(const std::vector<double>& v, double floor) {
  return v.empty() ? floor : std::max(floor, *std::max_element(v.begin(), v.end()));
}

}  // namespace

std::string timeSeriesSvg(const std::vector<double>& times, const std::vector<double>& values,
                          const std::string& title, const std::string& y_label, double y_min,
                          double y_max) {
  PlotArea a;
  a.t_max = largest(times, 1e-9);
  a.y_min = y_min;
  a.y_max = y_max;
  std::string svg = plotFrame(a, title, y_label);
  if (!times.empty()) {
    svg += "<polyline fill=\"none\" stroke=\"#0571b0\" stroke-width=\"1\" points=\"";
    const size_t n = std::min(times.size(), values.size());
    for (size_t i = 0; i < n; ++i) svg += num(a.x(times[i])) + "," + num(a.y(values[i])) + " ";
    svg += "\"/>\n";
  }
  return svg + "</svg>\n";
}

std::string scatterSvg(const std::vector<double>& times, const std::vector<double>& values,
                       const std::string& title, const std::string& y_label, double y_max,
                       const std::vector<size_t>& beyond,
                       const std::vector<std::string>& beyond_titles) {
  PlotArea a;
  a.t_max = largest(times, 1e-9);
  a.y_max = y_max > 0 ? y_max : 1.0;
  std::string svg = plotFrame(a, title, y_label);
  const size_t n = std::min(times.size(), values.size());
  for (size_t i = 0; i < n; ++i) {
    const size_t k = size_t(std::find(beyond.begin(), beyond.end(), i) - beyond.begin());
    if (k < beyond.size()) continue;
    svg += "<circle cx=\"" + num(a.x(times[i])) + "\" cy=\"" + num(a.y(values[i])) +
           "\" r=\"2\" fill=\"#0571b0\"/>\n";
  }
  // Off-scale values: a red triangle pointing up at the top edge, titled with the value.
  for (size_t k = 0; k < beyond.size() && beyond[k] < n; ++k) {
    const double x = a.x(times[beyond[k]]), y = a.top;
    svg += "<path d=\"M" + num(x - 5) + " " + num(y + 9) + " L" + num(x + 5) + " " + num(y + 9) +
           " L" + num(x) + " " + num(y + 1) + " Z\" fill=\"#ca0020\"><title>" +
           htmlEscape(k < beyond_titles.size() ? beyond_titles[k] : std::string()) +
           "</title></path>\n";
  }
  return svg + "</svg>\n";
}

std::string dotStripSvg(const std::vector<std::string>& labels,
                        const std::vector<std::vector<double>>& values,
                        const std::vector<double>& medians, const std::string& title,
                        const std::string& unit) {
  const double label_w = 140, axis_w = 400, row_h = 24, top = 22, bottom = 26;
  double x_max = 1e-9;
  for (const std::vector<double>& row : values) x_max = largest(row, x_max);
  const auto xOf = [&](double v) { return label_w + axis_w * v / x_max; };
  const double axis_y = top + row_h * double(labels.size());
  std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" +
                    num(label_w + axis_w + 60) + "\" height=\"" + num(axis_y + bottom) +
                    "\" role=\"img\" font-family=\"sans-serif\" font-size=\"12\"><title>" +
                    htmlEscape(title) + "</title>\n<text x=\"0\" y=\"14\">" + htmlEscape(title) +
                    "</text>\n";
  for (int k = 0; k <= 4; ++k) {
    const double v = x_max * k / 4, x = xOf(v);
    svg += "<line x1=\"" + num(x) + "\" y1=\"" + num(top) + "\" x2=\"" + num(x) + "\" y2=\"" +
           num(axis_y) + "\" stroke=\"#ddd\"/><text x=\"" + num(x - 8) + "\" y=\"" +
           num(axis_y + 16) + "\">" + num(v) + (k == 4 ? " " + htmlEscape(unit) : "") + "</text>\n";
  }
  for (size_t r = 0; r < labels.size(); ++r) {
    const double y = top + row_h * double(r) + row_h / 2;
    svg += "<text x=\"0\" y=\"" + num(y + 4) + "\">" + htmlEscape(labels[r]) + "</text>\n";
    for (double v : values[r])
      svg += "<circle cx=\"" + num(xOf(v)) + "\" cy=\"" + num(y) +
             "\" r=\"4\" fill=\"#0571b0\" fill-opacity=\"0.6\"><title>" + num(v) + " " +
             htmlEscape(unit) + "</title></circle>\n";
    if (r < medians.size())
      svg += "<line x1=\"" + num(xOf(medians[r])) + "\" y1=\"" + num(y - 8) + "\" x2=\"" +
             num(xOf(medians[r])) + "\" y2=\"" + num(y + 8) +
             "\" stroke=\"#333\" stroke-width=\"2\"><title>median " + num(medians[r]) + " " +
             htmlEscape(unit) + "</title></line>\n";
  }
  return svg + "</svg>\n";
}

}  // namespace cb
