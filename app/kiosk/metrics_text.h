// The kiosk's health as metrics in the Prometheus text exposition format (version 0.0.4), for
// node_exporter's textfile collector (a file <dir>/*.prom it reads at every scrape): counters
// (visits, strokes, saves failed, frames), gauges (frame rate, last input age, disk free and
// total, saving works) and info-style gauges labelled with the device state, the screen and the
// version. Every name starts with cloudbrush_.
#pragma once

#include <string>

#include "app/kiosk/health_status.h"

namespace cb {

// The metrics of `status`, HELP and TYPE lines first; label values escaped (\\, \", \n).
std::string metricsText(const HealthStatus& status, const std::string& version);

}  // namespace cb
