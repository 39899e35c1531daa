// The study report as one self-contained HTML page: inline CSS and SVG (svg_charts.h), no
// scripts, no links to fetch, so it opens offline and prints as it shows.
#pragma once

#include <string>

#include "app/study/study_report.h"

namespace cb {

std::string studyReportHtml(const StudyReport& report, const StudyReportOptions& options,
                            int scale_min, int scale_max);

}  // namespace cb
