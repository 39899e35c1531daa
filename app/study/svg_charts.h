// Inline SVG charts for the offline study report (no scripts, no fonts or files fetched): each
// function returns one <svg> element sized in CSS pixels, with a <title> for screen readers.
#pragma once

#include <string>
#include <vector>

#include "app/study/likert_statistics.h"

namespace cb {

// Escapes &, <, >, " and ' for XML/HTML text and attributes (and makes the text valid UTF-8).
std::string htmlEscape(const std::string& text);

// One horizontal bar per item, split into the share of each scale point (diverging colours from
// `scale_min` to the top of the scale), with n and the mean at the right.
std::string likertStackedBarsSvg(const std::vector<ItemSummary>& items, int scale_min);

// One row per construct: the mean as a dot with a ±1 SD whisker on the scale's axis.
std::string constructMeansSvg(const std::vector<ConstructSummary>& constructs, int scale_min,
                              int scale_max);

// A line of `values` against `times` (seconds), for a per-session trace such as pressure.
std::string timeSeriesSvg(const std::vector<double>& times, const std::vector<double>& values,
                          const std::string& title, const std::string& y_label, double y_min,
                          double y_max);

}  // namespace cb
