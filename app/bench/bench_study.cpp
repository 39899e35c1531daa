// `cloudbrush bench study`: the cost of a study's exports and report. Export times for a 256³
// volume (the bundled cumulus) as OpenVDB and as raw float32 + JSON, and of a 1280×720 frame as
// linear EXR + PNG; the pen-trace exports (InkML, samples/strokes/events CSV) and the HTML report
// for 20 synthetic sessions with 20 participants' answers. Baselines, measured in the same run:
// writing the volume's bytes with one fwrite (the floor for any volume file), and reading the 20
// journals (the floor for anything made from them). The journal's durability: the
// cost of writing one pen sample, and the stall of the fsync at each stroke end (p50, p99),
// against the same writes with a flush but no fsync. Files go to a temporary directory that is
// removed afterwards. Never fails on a missed target.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "app/bench/bench_report.h"
#include "app/bench/benches.h"
#include "app/cli/args.h"
#include "app/session/synthetic_session.h"
#include "app/study/construct_definitions.h"
#include "app/study/inkml_writer.h"
#include "app/study/likert_answers.h"
#include "app/study/render_export.h"
#include "app/study/session_trace.h"
#include "app/study/study_report.h"
#include "app/study/study_report_html.h"
#include "app/study/trace_csv.h"
#include "app/study/volume_export.h"
#include "app/volume/scene_generators.h"
#include "app/volume/volume_file.h"
#include "drivers/core/journal.h"

namespace cb {
namespace {

using Clock = std::chrono::steady_clock;

// Median over `repeats` runs of `run`, in ms.
template <typename Run>
double medianMs(int repeats, Run run) {
  std::vector<double> ms;
  for (int i = 0; i < repeats; ++i) {
    const auto t0 = Clock::now();
    run();
    ms.push_back(msSince(t0));
  }
  return median(ms);
}

constexpr int kScreenW = 1280, kScreenH = 720;

// One synthetic session: the reference strokes repeated `rounds` times, with a brush change
// before each stroke.
void writeSyntheticJournal(const std::string& path, int rounds, uint32_t seed) {
  JournalWriter journal;
  if (!journal.open(path)) throw std::runtime_error(journal.error());
  const PenDeviceInfo tablet = syntheticTablet(kScreenW, kScreenH);
  const std::vector<uint8_t> device = encodeDeviceInfo(tablet);
  journal.append(JournalRecordType::kDevice, 0, device.data(), device.size());
  journal.append(JournalRecordType::kMode, 0, "paint");
  int64_t t = 1'000'000;
  const std::vector<SyntheticStroke> strokes = referencePaintStrokes(kScreenW, kScreenH);
  for (int r = 0; r < rounds; ++r)
    for (size_t k = 0; k < strokes.size(); ++k) {
      journal.append(JournalRecordType::kUi, t, (k + seed) % 2 ? "brush=2d" : "brush=3d");
      for (const PenSample& s :
           syntheticPenSamples(strokes[k], tablet, kScreenW, kScreenH, 200.0, t)) {
        journal.appendPenSample(s);
        t = s.t_ns + 5'000'000;
      }
    }
  journal.close();
}

struct JournalWriteTimes {
  std::vector<double> sample_ns;      // per appended sample
  std::vector<double> stroke_end_ms;  // per stroke end: the sync (or only the flush)
};

// Writes the reference strokes `rounds` times as the painter does: one append per sample, and
// at each stroke end an fsync (`fsync_at_stroke_end`) or nothing more than the flush every
// append already makes (the baseline).
JournalWriteTimes timeJournalWrites(const std::string& path, int rounds, bool fsync_at_stroke_end) {
  JournalWriteTimes times;
  JournalWriter journal;
  if (!journal.open(path)) throw std::runtime_error(journal.error());
  const PenDeviceInfo tablet = syntheticTablet(kScreenW, kScreenH);
  const std::vector<SyntheticStroke> strokes = referencePaintStrokes(kScreenW, kScreenH);
  int64_t t = 1'000'000;
  for (int r = 0; r < rounds; ++r)
    for (const SyntheticStroke& stroke : strokes) {
      for (const PenSample& s : syntheticPenSamples(stroke, tablet, kScreenW, kScreenH, 200.0, t)) {
        const auto t0 = Clock::now();
        journal.appendPenSample(s);
        times.sample_ns.push_back(
            std::chrono::duration<double, std::nano>(Clock::now() - t0).count());
        t = s.t_ns + 5'000'000;
      }
      const auto t0 = Clock::now();
      if (fsync_at_stroke_end) journal.sync();
      times.stroke_end_ms.push_back(msSince(t0));
    }
  journal.close();
  return times;
}

std::string syntheticAnswers(int participants) {
  std::string csv = "participant";
  for (int q = 1; q <= 27; ++q) csv += ",Q" + std::to_string(q);
  csv += "\n";
  uint32_t state = 12345;
  for (int p = 0; p < participants; ++p) {
    csv += "P" + std::to_string(p + 1);
    for (int q = 0; q < 27; ++q) {
      state = state * 1664525u + 1013904223u;  // LCG (Numerical Recipes): answers 1..5
      csv += "," + std::to_string(1 + (state >> 16) % 5);
    }
    csv += "\n";
  }
  return csv;
}

// The volume's exports (.vdb, .cbvol) against a plain fwrite of its floats.
void benchVolumeExport(long grid, long repeats, const std::filesystem::path& dir,
                       BenchReport& report) {
  const Volume volume = makeBundledCumulus(glm::ivec3(int(grid)));
  std::printf("volume %ld^3 (%.1f MiB of float32)\n", grid,
              double(volume.voxelCount()) * 4 / (1 << 20));
  const std::vector<float> dense = volume.toDense();
  const double fwrite_ms = medianMs(int(repeats), [&] {
    std::FILE* f = std::fopen((dir / "plain.raw").c_str(), "wb");
    if (!f) throw std::runtime_error((dir / "plain.raw").string() + ": cannot create");
    std::fwrite(dense.data(), sizeof(float), dense.size(), f);
    std::fclose(f);
  });
  double vdb_ms = 0, cbvol_ms = 0;
  {
    std::vector<double> vdb, cbvol;
    for (long i = 0; i < repeats; ++i) {
      // exportVolume writes the .vdb then the .cbvol; timed as one and the .cbvol alone.
      const auto t0 = Clock::now();
      const VolumeExport e = exportVolume(volume, dir.string(), "cloud");
      const double both = msSince(t0);
      const auto t1 = Clock::now();
      saveVolume(volume, (dir / "cloud.cbvol").string());
      const double raw = msSince(t1);
      cbvol.push_back(raw);
      vdb.push_back(volumeExportHasVdb() ? both - raw : 0.0);
    }
    vdb_ms = median(vdb);
    cbvol_ms = median(cbvol);
  }
  std::printf("export .vdb %.1f ms (%s), .cbvol %.1f ms; plain fwrite %.1f ms\n", vdb_ms,
              volumeExportHasVdb() ? "OpenVDB" : "not built", cbvol_ms, fwrite_ms);
  if (volumeExportHasVdb())
    report.figure("vdb_export_ms", vdb_ms);
  else
    report.note("vdb_export_ms", "built without OpenVDB");
  report.figure("raw_json_export_ms", cbvol_ms);
  report.baseline("fwrite_volume_ms", fwrite_ms);
}

// A 1280x720 frame's EXR + PNG export.
void benchRenderExport(long repeats, const std::filesystem::path& dir, BenchReport& report) {
  ImageRgbaF frame;
  frame.width = 1280;
  frame.height = 720;
  frame.pixels.resize(size_t(frame.width) * frame.height * 4);
  for (size_t i = 0; i < frame.pixels.size(); ++i)
    frame.pixels[i] = float((i * 2654435761u) % 1000) / 1000.0f;
  const double render_ms =
      medianMs(int(repeats), [&] { exportRender(frame, dir.string(), "frame"); });
  std::printf("render export 1280x720 EXR + PNG %.1f ms\n", render_ms);
  report.figure("render_exr_png_export_ms", render_ms);
}

// The journal's cost per sample and at a stroke's end, with fsync against without.
void benchJournalWrites(const std::filesystem::path& dir, BenchReport& report) {
  // Baseline first, then with fsync, into files of the same size in the same directory.
  const JournalWriteTimes plain =
      timeJournalWrites((dir / "journal-nofsync.cbj").string(), 50, false);
  const JournalWriteTimes synced =
      timeJournalWrites((dir / "journal-fsync.cbj").string(), 50, true);
  const double per_sample = median(synced.sample_ns), per_sample_plain = median(plain.sample_ns);
  std::printf(
      "journal: %zu samples, %zu strokes: write %.0f ns/sample (median; p99 %.0f ns); fsync "
      "at stroke end p50 %.3f ms, p99 %.3f ms; without fsync %.0f ns/sample, stroke end "
      "p50 %.4f ms, p99 %.4f ms\n",
      synced.sample_ns.size(), synced.stroke_end_ms.size(), per_sample,
      percentile(synced.sample_ns, 99), percentile(synced.stroke_end_ms, 50),
      percentile(synced.stroke_end_ms, 99), per_sample_plain, percentile(plain.stroke_end_ms, 50),
      percentile(plain.stroke_end_ms, 99));
  report.figure("journal_write_ns_per_sample", per_sample);
  report.figure("journal_write_p99_ns", percentile(synced.sample_ns, 99));
  report.figure("stroke_end_fsync_p50_ms", percentile(synced.stroke_end_ms, 50));
  report.figure("stroke_end_fsync_p99_ms", percentile(synced.stroke_end_ms, 99));
  report.baseline("journal_write_ns_per_sample_no_fsync", per_sample_plain);
  report.baseline("stroke_end_no_fsync_p50_ms", percentile(plain.stroke_end_ms, 50));
  report.baseline("stroke_end_no_fsync_p99_ms", percentile(plain.stroke_end_ms, 99));
}

// Reading N synthetic sessions' journals, loading their traces, the InkML + CSV exports and the
// HTML report.
void benchTraceExports(long session_count, long repeats, const std::filesystem::path& dir,
                       BenchReport& report) {
  std::vector<std::string> journals;
  for (long s = 0; s < session_count; ++s) {
    journals.push_back((dir / ("session-" + std::to_string(s) + ".cbj")).string());
    writeSyntheticJournal(journals.back(), 10, uint32_t(s));
  }
  std::vector<SessionTrace> traces;
  const double read_ms = medianMs(int(repeats), [&] {
    for (const std::string& path : journals) readJournal(path);
  });
  const double load_ms = medianMs(int(repeats), [&] {
    traces.clear();
    for (const std::string& path : journals) traces.push_back(loadSessionTrace(path));
  });
  size_t samples = 0;
  for (const SessionTrace& t : traces) samples += t.samples.size();
  const double trace_ms = medianMs(int(repeats), [&] {
    std::ofstream ink(dir / "traces.inkml"), csv(dir / "samples.csv"), st(dir / "strokes.csv"),
        ev(dir / "events.csv");
    writeInkml(ink, traces);
    writeSamplesCsv(csv, traces);
    writeStrokesCsv(st, traces);
    writeEventsCsv(ev, traces);
  });
  std::istringstream answers_text(syntheticAnswers(int(session_count)));
  const LikertAnswers answers = readLikertAnswers(answers_text, "synthetic answers");
  StudyReportOptions options;
  options.constructs = appendixCSections();
  const double report_ms = medianMs(int(repeats), [&] {
    const StudyReport r = computeStudyReport(answers, options, traces);
    std::ofstream(dir / "report.html") << studyReportHtml(r, options, 1, 5);
  });
  std::printf(
      "%ld sessions, %zu samples: read journals %.1f ms, load traces %.1f ms, InkML + "
      "CSV export %.1f ms, report (answers + sessions, HTML) %.1f ms\n",
      session_count, samples, read_ms, load_ms, trace_ms, report_ms);
  report.figure("trace_load_ms", load_ms);
  report.figure("trace_export_ms", trace_ms);
  report.figure("report_ms", report_ms);
  report.figure("sessions", double(session_count));
  report.figure("samples", double(samples));
  report.baseline("read_journals_ms", read_ms);
}

}  // namespace

int benchStudy(int argc, char** argv) {
  Args args(argc, argv, {"help"});
  if (args.has("help")) {
    std::printf(
        "usage: cloudbrush bench study [--grid N] [--sessions N] [--repeats N]\n"
        "  export times for a grid³ volume (default 256) and a 1280x720 frame; trace exports\n"
        "  and the HTML report for N synthetic sessions (default 20); medians of --repeats runs\n"
        "  (default 3)\n");
    return 0;
  }
  const long grid = args.getInt("grid", 256);
  const long session_count = args.getInt("sessions", 20);
  const long repeats = args.getInt("repeats", 3);
  if (!args.error().empty() || grid < 8 || grid > 512 || session_count < 1 || session_count > 200 ||
      repeats < 1 || repeats > 50) {
    std::fprintf(stderr,
                 "cloudbrush bench study: %s (--grid 8..512, --sessions 1..200, --repeats 1..50)\n",
                 args.error().empty() ? "option out of range" : args.error().c_str());
    return 2;
  }
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("cloudbrush-bench-study-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  BenchReport report("study");
  try {
    benchVolumeExport(grid, repeats, dir, report);
    benchRenderExport(repeats, dir, report);
    benchJournalWrites(dir, report);
    benchTraceExports(session_count, repeats, dir, report);
  } catch (const std::exception& e) {
    std::filesystem::remove_all(dir);
    std::fprintf(stderr, "cloudbrush bench study: %s\n", e.what());
    return 1;
  }
  std::filesystem::remove_all(dir);
  report.print();
  return 0;
}

}  // namespace cb
