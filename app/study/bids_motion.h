// A session's pen trace in a BIDS dataset as a motion recording (BIDS specification 1.9,
// "Motion"; datatype motion/, tracking system "tablet"): the pen tablet tracks one point, the
// pen, whose tip position (POS, mm), tilt (ORNT, degrees from vertical) and pressure, hover
// distance, tip contact, proximity, buttons and tool (MISC) are channels. Motion rather than
// beh/physio because the tablet is a tracking system (the spec's channel types, components,
// tracked point and units fit each pen channel) and because its reports come when the pen
// moves, not at a fixed rate: motion's LATENCY channel carries each sample's own time (seconds
// after the journal's first record, the origin of the session's events too), where physio
// assumes a constant SamplingFrequency.
//
//   _motion.tsv    one row per raw pen sample, no header (BIDS), columns as in _channels.tsv
//   _channels.tsv  name, component, type, tracked_point, units, description of each column
//   _motion.json   TaskName, the tablet, SamplingFrequency (the median report rate),
//                  SamplingFrequencyEffective (samples over the recording's span), durations and
//                  channel counts
#pragma once

#include <string>

#include "app/study/session_trace.h"

namespace cb {

std::string bidsMotionTsv(const SessionTrace& trace);
std::string bidsChannelsTsv();
// `task_name`: the TaskName shared by the dataset's sidecars.
std::string bidsMotionJson(const SessionTrace& trace, const std::string& task_name,
                           const std::string& task_description);

}  // namespace cb
