// The kiosk's start-up failure path, shared by `cloudbrush kiosk` and the painter's --kiosk.
#pragma once

#include <atomic>
#include <string>

#include "app/kiosk/kiosk_service.h"
#include "app/render/gl/display.h"
#include "app/shell/painter/paint_loop.h"

namespace cb {

// The exit status after the error screen was stopped (the kiosk itself never ran).
inline constexpr int kKioskErrorScreenExitStatus = 3;

// Logs `problem` ("FILE:LINE: what"), makes it health.json's last_error and shows it on
// KioskErrorScreen until `stop` is set (or the scripted frame / seconds limit of `options`),
// with the service's READY, STATUS and watchdog pings going on, so that systemd keeps it up
// instead of restart-looping. Returns kKioskErrorScreenExitStatus (1 when drawing fails).
int runKioskErrorScreen(Display& display, KioskService& service, const std::string& problem,
                        const PaintLoopOptions& options, const std::atomic<bool>* stop);

}  // namespace cb
