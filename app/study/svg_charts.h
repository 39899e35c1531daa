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

// Dots of `values` against `times` (seconds) on 0..y_max. The values at the indices `beyond`
// lie off the scale: each is a red triangle on the top edge titled with beyond_titles[k], so one
// artefact does not squash every other point to the floor.
std::string scatterSvg(const std::vector<double>& times, const std::vector<double>& values,
                       const std::string& title, const std::string& y_label, double y_max,
                       const std::vector<size_t>& beyond,
                       const std::vector<std::string>& beyond_titles);

// One row per label: its values as dots on a shared axis from 0, the row's median as a tick.
std::string dotStripSvg(const std::vector<std::string>& labels,
                        const std::vector<std::vector<double>>& values,
                        const std::vector<double>& medians, const std::string& title,
                        const std::string& unit);

}  // namespace cb
