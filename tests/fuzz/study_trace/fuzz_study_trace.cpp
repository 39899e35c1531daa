// Fuzz target: a journal from elsewhere through the study's pen-trace exports (journal parser,
// session trace, stroke measures, InkML, the three CSV tables, the report's session figures).
// Records may be well-formed but nonsensical: any timestamps, NaN positions, unknown types.
#include <cstdint>
#include <sstream>

#include "app/study/inkml_writer.h"
#include "app/study/study_report.h"
#include "app/study/trace_csv.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const cb::JournalReadResult journal = cb::parseJournal(data, size, "fuzz");
  try {
    const cb::SessionTrace trace = cb::sessionTraceFromJournal(journal, "fuzz", "fuzz");
    std::ostringstream out;
    cb::writeInkml(out, {trace});
    cb::writeSamplesCsv(out, {trace});
    cb::writeStrokesCsv(out, {trace});
    cb::writeEventsCsv(out, {trace});
    (void)cb::sessionFigures(trace);
  } catch (const cb::StudyInputError&) {
  }
  return 0;
}
