// The pen-trace CSV tables of one or many sessions (one header, then the rows of every session
// in the order given, each row starting with the session id), read as they are by R and pandas:
//
//   samples.csv  one row per raw pen sample:
//     participant,session,sample,t_ns,t_s,x_raw,y_raw,x_mm,y_mm,pressure_raw,pressure,
//     tilt_x_raw,tilt_y_raw,tilt_x_deg,tilt_y_deg,distance_raw,distance,buttons,tip,
//     in_proximity,tool,tool_id,tool_serial,gesture,stroke,task
//     t_ns is the journal's monotonic timestamp; t_s is seconds after the session's first
//     record; tip is 1 while the tip bit is set; gesture is the strokes.csv row the sample
//     belongs to, stroke the painter's stroke index (rows of kind stroke), else NA.
//   strokes.csv  one row per gesture (stroke_table.h: painter strokes, erase drags, menu taps,
//     each marked in kind; stroke is the painter's index, NA for other kinds):
//     participant,session,gesture,kind,stroke,start_s,duration_s,samples,path_length_mm,
//     mean_pressure,max_pressure,mean_tilt_deg,speed_mm_s,brush,mode,mapping_ms,task
//   events.csv   one row per non-sample record (UI and mode changes, markers, calibration,
//     session metadata, device):
//     participant,session,t_s,record,kind,key,value,task
//     kind is mode|ui|marker|calibration|session|device|type-N; for ui, key and value are the
//     two sides of "key=value" (key alone for undo/redo/delete_all); for mode, key is "mode".
//
// Numbers are written to read back bit for bit (csv_text.h); missing values are NA.
#pragma once

#include <ostream>
#include <vector>

#include "app/study/session_trace.h"

namespace cb {

// Header and rows of many sessions.
void writeSamplesCsv(std::ostream& out, const std::vector<SessionTrace>& sessions);
void writeStrokesCsv(std::ostream& out, const std::vector<SessionTrace>& sessions);
void writeEventsCsv(std::ostream& out, const std::vector<SessionTrace>& sessions);

// The same in pieces, so a study is written one session at a time (one session in memory).
void writeSamplesCsvHeader(std::ostream& out);
void writeSamplesCsvRows(std::ostream& out, const SessionTrace& trace);
void writeStrokesCsvHeader(std::ostream& out);
void writeStrokesCsvRows(std::ostream& out, const SessionTrace& trace);
void writeEventsCsvHeader(std::ostream& out);
void writeEventsCsvRows(std::ostream& out, const SessionTrace& trace);

// The name events.csv gives a record type ("mode", "ui", ..., "type-9" for unknown types).
std::string eventKindName(JournalRecordType type);

}  // namespace cb
