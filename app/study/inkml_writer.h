// Pen traces as W3C InkML (Ink Markup Language, W3C Recommendation 20 September 2011,
// https://www.w3.org/TR/InkML/). One <ink> document holds one or many sessions:
//
//   per session, a <definitions> block with its <context xml:id="ctx-N">, holding its
//     <inkSource> (the capture device: model = the device name, USB ids, ranges and
//     resolutions as srcProperty, the active area in mm) and its <traceFormat>:
//       X, Y    decimal, mm from the active area's top-left corner (+x right, +y towards the user)
//       F       integer, device pressure units 0..pressure_max (max attribute)
//       OTx,OTy decimal, deg: tilt from vertical in the x-z and y-z planes
//       T       decimal, ms after the session's first journal record (exact to the ns)
//     (the first Device record of the journal: a device change mid-session is not shown)
//   then its <traceGroup contextRef="#ctx-N">, annotated with the session id, with one
//   <trace> per run of samples: type="penDown" while the tip bit is set, type="penUp" while
//   hovering. Every journal sample is in exactly one trace, in order, so the document carries
//   every sample (X, Y with 17 significant digits and OTx, OTy with 9 read back bit for bit).
#pragma once

#include <ostream>
#include <vector>

#include "app/study/session_trace.h"

namespace cb {

void writeInkml(std::ostream& out, const std::vector<SessionTrace>& sessions);

// The same in pieces, so a study is written one session at a time: beginInkml, then
// writeInkmlSession for session n = 0, 1, …, then endInkml.
void beginInkml(std::ostream& out);
void writeInkmlSession(std::ostream& out, const SessionTrace& trace, size_t n);
void endInkml(std::ostream& out);

// The channel names, in trace order.
inline constexpr const char* kInkmlChannels[] = {"X", "Y", "F", "OTx", "OTy", "T"};

}  // namespace cb
