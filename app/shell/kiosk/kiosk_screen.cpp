#include "app/shell/kiosk/kiosk_screen.h"

#include <malloc.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "app/core/atomic_file.h"
#include "app/kiosk/data_retention.h"
#include "app/kiosk/disk_space.h"
#include "app/kiosk/unsaved_visit.h"
#include "app/render/gl/gl.h"
#include "app/session/session_replay.h"
#include "app/shell/keymap.h"
#include "app/shell/kiosk/gallery_capture.h"
#include "drivers/core/clock.h"
#include "drivers/core/pen_source.h"

namespace cb {
namespace {

namespace fs = std::filesystem;

bool isModifierKey(uint32_t keysym) {
  return keysym >= 0xffe1 && keysym <= 0xffee;  // Shift, Control, Caps, Meta, Alt, Super, Hyper
}

uint32_t lowerLetter(uint32_t k) {
  return k >= 'A' && k <= 'Z' ? k - 'A' + 'a' : k;
}

std::string utcStamp() {
  char stamp[32];
  const std::time_t now = std::time(nullptr);
  std::strftime(stamp, sizeof stamp, "%Y%m%dT%H%M%SZ", std::gmtime(&now));
  return stamp;
}

AttractOptions attractOptions(const KioskSetup& setup) {
  AttractOptions a;
  a.orbit_degrees_per_second = setup.config.orbit_degrees_per_second;
  a.hold_s = setup.config.attract_hold_seconds;
  a.speed = setup.config.attract_speed;
  a.grid = setup.visitor_settings.grid;
  a.brush = setup.brush;
  a.mapping = setup.mapping;
  a.render = setup.render;
  a.render.scale = setup.moving_scale;
  a.light = setup.light;
  // After the replay the attract loop morphs into visitors' clouds (attract_screen.h).
  if (setup.config.gallery_enabled) a.gallery_dir = setup.data_dir + "/gallery";
  return a;
}

}  // namespace

const char* KioskScreen::stateName(State state) {
  switch (state) {
    case State::kAttract:
      return "attract";
    case State::kVisitor:
      return "visitor";
    case State::kReconnect:
      return "reconnect";
    case State::kOperator:
      return "operator";
    case State::kCalibrate:
      return "calibrate";
  }
  return "?";
}

KioskScreen::KioskScreen(Display& display, VolumeRenderer& renderer, PaintScreen& paint,
                         PenSource* pen, const Clock& clock, KioskSetup setup)
    : display_(display),
      renderer_(renderer),
      paint_(paint),
      pen_(pen),
      clock_(clock),
      setup_(std::move(setup)),
      session_dir_(setup_.data_dir + "/sessions"),
      attract_(renderer, clock, setup_.attract_journal, attractOptions(setup_), &ui_),
      reconnect_(&ui_),
      // The lockout's wall time runs on the injected clock from the real wall time at start.
      pin_guard_(
          setup_.data_dir,
          [&clock, start_ns = clock.nowNs(),
           start_s =
               std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch())
                   .count()] { return start_s + double(clock.nowNs() - start_ns) / 1e9; }),
      panel_(clock, &pin_guard_, &ui_),
      gallery_(setup_.data_dir + "/gallery", setup_.config.gallery_quota_bytes,
               setup_.config.gallery_keep_days, setup_.config.min_free_bytes),
      operator_log_(setup_.data_dir + "/operator.log"),
      clock_start_ns_(clock.nowNs()),
      file_time_start_(std::filesystem::file_time_type::clock::now()) {
  std::vector<DisplayEvent> keys;
  std::string error;
  if (!parseKeyList(setup_.config.operator_keys, &keys, &error) || keys.size() != 1) {
    std::fprintf(stderr,
                 "cloudbrush kiosk: [operator] keys '%s' is not one key combination (%s); using "
                 "ctrl+alt+o\n",
                 setup_.config.operator_keys.c_str(), error.c_str());
    keys = {DisplayEvent::key('o', DisplayEvent::kCtrl | DisplayEvent::kAlt)};
  }
  operator_keys_ = keys.front();
  std::error_code ec;
  std::filesystem::create_directories(setup_.data_dir, ec);
  if (ec)
    std::fprintf(stderr, "cloudbrush kiosk: data dir %s: %s\n", setup_.data_dir.c_str(),
                 ec.message().c_str());
  if (!pin_guard_.problem().empty())
    std::fprintf(stderr, "cloudbrush kiosk: operator PIN: %s\n", pin_guard_.problem().c_str());
  if (!pin_guard_.hasPin())
    std::fprintf(stderr,
                 "cloudbrush kiosk: NO OPERATOR PIN is set: the operator key combination asks for "
                 "a new one (or set it beforehand: cloudbrush kiosk --set-pin --data-dir %s)\n",
                 setup_.data_dir.c_str());
  for (const std::string& problem : attract_.problems())
    std::fprintf(stderr, "cloudbrush kiosk: %s\n", problem.c_str());
  updateTexts();
  // The painter speaks to visitors in the kiosk's words only (visitor_words.h).
  paint_.setVisitorText([this](const std::string& key) { return setup_.texts.text(key); },
                        setup_.texts.allText());
  for (const std::string& path : gallery_.removeIncomplete())
    std::fprintf(stderr,
                 "cloudbrush kiosk: gallery: removed %s (a save the kiosk did not finish)\n",
                 path.c_str());
  cleanUpOldData();
  std::string why;
  if (!roomToWrite(0, &why)) setStorageProblem("NOT SAVING: " + why);
  recoverUnsavedVisit();
  // The operator's last press calibration (P on the panel), for every visitor.
  const std::string range_path = setup_.data_dir + "/pressure_range.toml";
  std::error_code range_ec;
  if (std::filesystem::exists(range_path, range_ec)) {
    std::ifstream in(range_path);
    const std::string text{std::istreambuf_iterator<char>(in), {}};
    std::string range_error = in ? "" : std::string("cannot be read: ") + std::strerror(errno);
    if (range_error.empty()) pressure_range_ = pressureRangeFromToml(text, &range_error);
    if (!pressure_range_)
      std::fprintf(stderr,
                   "cloudbrush kiosk: %s: %s (ignored: visitors get the pen's whole range)\n",
                   range_path.c_str(), range_error.c_str());
    else
      std::fprintf(stderr, "cloudbrush kiosk: pressure range %.3f..%.3f from %s\n",
                   double(pressure_range_->lo), double(pressure_range_->hi), range_path.c_str());
  }
  prepareVisitor();
  last_input_ns_ = clock_.nowNs();
  setState(State::kAttract);
}

KioskScreen::~KioskScreen() {
  if (calibration_)  // stopped (service stop, signal) in the middle of the operator's calibration
    logOperator(std::string(OperatorPanelScreen::actionName(
                    calibrating_pressure_ ? OperatorActionKind::kCalibratePressure
                                          : OperatorActionKind::kCalibrate)) +
                " abandoned: the kiosk stopped (nothing saved)");
  if (visitor_) visitor_->recordTo(nullptr, clock_.nowNs());
  closeJournal();
}

KioskCounts KioskScreen::counts() const {
  KioskCounts c;
  c.visits = visits_;
  c.strokes = strokes();
  c.gallery_saved = long(gallery_saved_.size());
  c.saves_failed = saves_failed_;
  c.screen = stateName(state_);
  return c;
}

void KioskScreen::updateTexts() {
  const KioskTexts& t = setup_.texts;
  std::string notice;
  const auto days = [](double d) { return std::to_string(long(std::lround(d))); };
  if (setup_.config.gallery_enabled)
    notice = t.format("gallery_notice", {{"days", days(setup_.config.gallery_keep_days)}});
  if (setup_.record_journals)
    notice += (notice.empty() ? "" : "\n") +
              t.format("recording_notice", {{"days", days(setup_.config.journal_keep_days)}});
  attract_.setTexts(t.text("invitation"), t.text("invitation_hint"), notice);
}

void KioskScreen::setState(State state) {
  state_ = state;
  reconnect_drawn_.reset();
  std::string status;
  switch (state) {
    case State::kAttract:
      status = "attract loop: waiting for a visitor";
      break;
    case State::kVisitor:
      status = "visitor " + std::to_string(visits_) + " painting";
      break;
    case State::kReconnect:
      status = "the pen was unplugged: showing \"reconnect the pen\"";
      break;
    case State::kOperator:
      status = "operator panel";
      break;
    case State::kCalibrate:
      status = "operator calibrating the pen";
      break;
  }
  std::fprintf(stderr, "cloudbrush kiosk: %s\n", status.c_str());
  if (setup_.on_status) setup_.on_status(status);
}

void KioskScreen::input(int64_t now) {
  last_input_ns_ = now;
  if (setup_.on_input) setup_.on_input();
}

std::filesystem::file_time_type KioskScreen::fileTimeNow() const {
  return file_time_start_ + std::chrono::duration_cast<std::filesystem::file_time_type::duration>(
                                std::chrono::nanoseconds(clock_.nowNs() - clock_start_ns_));
}

void KioskScreen::cleanUpOldData() {
  // Ages on the kiosk's clock: files carry its time (closeJournal, saveToGallery).
  std::string error;
  const auto now = fileTimeNow();
  for (const std::string& path :
       deleteFilesOlderThan(session_dir_, ".cbj", setup_.config.journal_keep_days, now, &error))
    std::fprintf(stderr, "cloudbrush kiosk: deleted %s (older than %.0f days)\n", path.c_str(),
                 setup_.config.journal_keep_days);
  // The newest entry stays even when it alone is over the quota.
  const GalleryCleanup cleanup =
      gallery_.enforce(gallery_saved_.empty() ? -1 : gallery_saved_.back(), now, &error);
  for (long n : cleanup.removed_for_age)
    std::fprintf(stderr, "cloudbrush kiosk: gallery %06ld deleted (older than %.0f days)\n", n,
                 setup_.config.gallery_keep_days);
  for (long n : cleanup.removed_for_quota)
    std::fprintf(stderr, "cloudbrush kiosk: gallery %06ld deleted (over the quota)\n", n);
  if (!error.empty()) std::fprintf(stderr, "cloudbrush kiosk: cleanup: %s\n", error.c_str());
}

void KioskScreen::prepareVisitor() {
  // A fresh session for the next visitor (no undo into the previous visitor's cloud), made while
  // nobody waits: allocating a 256³ sky takes a while, and the hand-over must be at once.
  auto session =
      std::make_unique<PaintSession>(setup_.visitor_settings, setup_.brush, setup_.mapping);
  if (!setup_.render_settings.empty()) session->setRenderSettings(setup_.render_settings, 0);
  session->setStartingLight(setup_.light);
  session->setStartingStyle(setup_.style);
  if (pressure_range_) {
    std::string error;
    if (!session->apply(ui::SetPressureRange{pressure_range_->lo, pressure_range_->hi}, 0, &error))
      std::fprintf(stderr, "cloudbrush kiosk: pressure range: %s\n", error.c_str());
  }
  paint_.attachPen(pen_, session.get());
  if (visitor_) {
    visitor_->recordTo(nullptr, clock_.nowNs());
    strokes_done_ += long(visitor_->strokesMapped());
  }
  visitor_ = std::move(session);
  next_visitor_pending_ = false;
  // The finished visitor's sky and undo history are freed now; hand the pages back, so the
  // kiosk's resident memory after each reset is what the next visit needs, not the high-water
  // mark of the largest visit so far (weeks of uptime).
  malloc_trim(0);
}

void KioskScreen::beginVisit(int64_t now) {
  ++visits_;
  if (!visitor_ || next_visitor_pending_) prepareVisitor();
  if (setup_.record_journals) openJournal(now);
  notice_.clear();
  input(clock_.nowNs());
  setState(State::kVisitor);
}

void KioskScreen::openJournal(int64_t now) {
  // A journal of the visitor's own, when the disk has room for it above the floor (a full disk
  // leaves no 0-byte journals behind).
  journal_failed_ = false;
  const std::string path =
      session_dir_ + "/" + utcStamp() + "-visit" + std::to_string(visits_) + ".cbj";
  std::string why;
  if (!roomToWrite(0, &why)) {
    ++saves_failed_;
    reportProblem("NOT RECORDING visitor " + std::to_string(visits_) + ": " + why);
    setStorageProblem("NOT SAVING: " + why);
    return;
  }
  std::error_code ec;
  std::filesystem::create_directories(session_dir_, ec);
  journal_ = std::make_unique<JournalWriter>();
  if (ec || !journal_->open(path)) {
    const std::string error = path + ": " + (ec ? ec.message() : journal_->error());
    closeJournal();
    ++saves_failed_;
    reportProblem("NOT RECORDING: " + error);
    setStorageProblem("NOT SAVING journals: " + error);
    return;
  }
  visitor_->recordTo(journal_.get(), now);
  // Until the visit ends, the next start knows whose cloud a kill would leave unsaved.
  std::string error;
  if (!writeUnsavedVisit(setup_.data_dir, {fs::path(path).filename().string(), std::nullopt},
                         &error))
    reportProblem("visit record (a crash would not keep this cloud): " + error);
  std::printf("journal: %s\n", path.c_str());
  std::fflush(stdout);
}

void KioskScreen::closeJournal() {
  if (!journal_) return;
  const std::string path = journal_->path();
  journal_->close();
  journal_.reset();
  std::error_code stamp_ec;
  if (!path.empty())
    std::filesystem::last_write_time(path, fileTimeNow(), stamp_ec);  // the kiosk clock's time
  std::string error;
  if (!clearUnsavedVisit(setup_.data_dir, &error))
    std::fprintf(stderr, "cloudbrush kiosk: %s\n", error.c_str());
  std::error_code ec;
  if (!path.empty() && std::filesystem::file_size(path, ec) == 0 && !ec)
    std::filesystem::remove(path, ec);  // nothing could be written: no empty journal stays
}

void KioskScreen::recoverUnsavedVisit() {
  // The kiosk was killed mid-visit (unsaved_visit.h): that visitor's journal into the gallery.
  std::string error;
  const std::optional<UnsavedVisit> visit = readUnsavedVisit(setup_.data_dir, &error);
  if (!visit) {
    if (error.empty()) return;
    reportProblem("killed visit not recovered: " + error + " (removed)");
    clearUnsavedVisit(setup_.data_dir, &error);
    return;
  }
  const std::string journal = session_dir_ + "/" + visit->journal;
  const long newest = gallery_.lastNumber();
  const auto done = [&](const std::string& what) {
    std::fprintf(stderr, "cloudbrush kiosk: killed visit (journal %s): %s\n", journal.c_str(),
                 what.c_str());
    std::string clear_error;
    if (!clearUnsavedVisit(setup_.data_dir, &clear_error)) reportProblem(clear_error);
  };
  if (visit->gallery_newest_before && newest > *visit->gallery_newest_before)
    return done("its cloud was saved as " + std::to_string(newest) + " before the last stop");
  if (!setup_.config.gallery_enabled) return done("not replayed: the gallery is off");
  const SessionReplay replay =
      replaySession(readJournal(journal), setup_.brush, setup_.mapping, setup_.visitor_settings);
  if (!replay.session || !replay.session->volume().hasDensity())
    return done(replay.session ? "nothing was painted" : "unreadable: " + replay.journal_error);
  if (!writeUnsavedVisit(setup_.data_dir, {visit->journal, newest}, &error)) {
    reportProblem("killed visit not recovered: " + error);
    return;  // tried again at the next start
  }
  GallerySave save;
  const bool ok = saveToGallery(gallery_, renderer_, replay.session->volume(),
                                replay.session->camera(), replay.session->light(), setup_.render,
                                display_.width(), display_.height(), fileTimeNow(), &save, &error);
  glBindFramebuffer(GL_FRAMEBUFFER, display_.framebuffer());
  glViewport(0, 0, display_.width(), display_.height());
  if (!ok) {
    ++saves_failed_;
    reportProblem("gallery: NOT SAVED (killed visit, journal " + journal + "): " + error);
    return done("its cloud could not be saved");
  }
  gallery_saved_.push_back(save.number);
  char what[160];
  std::snprintf(what, sizeof what, "replayed (%u strokes%s) and saved to the gallery as %06ld",
                replay.strokes_mapped, replay.complete() ? "" : ", up to a damaged record",
                save.number);
  done(what);
}

bool KioskScreen::roomToWrite(uint64_t need_bytes, std::string* why) {
  std::string error;
  const GalleryRoom room = gallery_.makeRoom(need_bytes, -1, &error);
  for (long n : room.removed)
    std::fprintf(stderr,
                 "cloudbrush kiosk: gallery %06ld deleted (to keep %.0f MB free on the disk)\n", n,
                 double(setup_.config.min_free_bytes) / 1048576.0);
  if (room.enough || !room.free_bytes) return true;  // unknown: try, and a failure says why
  char text[200];
  std::snprintf(text, sizeof text,
                "disk full: %.1f MB free on the data dir's disk, %.1f MB kept free "
                "(gallery.min_free_mb)%s",
                double(*room.free_bytes) / 1048576.0,
                double(setup_.config.min_free_bytes) / 1048576.0,
                need_bytes ? " + room for one entry" : "");
  *why = text;
  return false;
}

void KioskScreen::reportProblem(const std::string& problem) {
  std::fprintf(stderr, "cloudbrush kiosk: %s\n", problem.c_str());
  if (setup_.on_problem) setup_.on_problem(problem);
}

void KioskScreen::setStorageProblem(const std::string& problem) {
  if (problem == storage_problem_) return;
  storage_problem_ = problem;
  if (problem.empty())
    std::fprintf(stderr, "cloudbrush kiosk: storage: saving works again (%s)\n",
                 storageSummary().c_str());
  else
    std::fprintf(stderr, "cloudbrush kiosk: storage: %s\n", problem.c_str());
  if (setup_.on_storage) setup_.on_storage(problem);
}

void KioskScreen::checkStorage(int64_t now) {
  // Recovers by itself: once the floor (plus an entry, with the gallery on) is free again.
  if (storage_problem_.empty() || double(now - storage_checked_ns_) / 1e9 < kStorageCheckS) return;
  storage_checked_ns_ = now;
  std::string why;
  if (roomToWrite(setup_.config.gallery_enabled ? gallery_.typicalEntryBytes() : 0, &why))
    setStorageProblem("");
}

std::string KioskScreen::storageSummary() {
  std::string error;
  const std::optional<DiskSpace> disk = diskSpaceAt(setup_.data_dir, &error);
  if (!disk) return error;
  char text[96];
  std::snprintf(text, sizeof text, "%.1f MB free of %.1f MB", double(disk->free_bytes) / 1048576.0,
                double(disk->total_bytes) / 1048576.0);
  return text;
}

void KioskScreen::keepFinishedCloud(const std::string& why) {
  if (!setup_.config.gallery_enabled || !visitor_ || !paint_.hasPaint()) return;
  GallerySave save;
  std::string error;
  const auto started = std::chrono::steady_clock::now();
  const bool ok = saveToGallery(gallery_, renderer_, visitor_->volume(), paint_.shownCamera(),
                                visitor_->light(), setup_.render, display_.width(),
                                display_.height(), fileTimeNow(), &save, &error);
  glBindFramebuffer(GL_FRAMEBUFFER, display_.framebuffer());
  glViewport(0, 0, display_.width(), display_.height());
  for (long n : save.cleanup.removed_for_space)
    std::fprintf(stderr,
                 "cloudbrush kiosk: gallery %06ld deleted (to keep %.0f MB free on the disk)\n", n,
                 double(setup_.config.min_free_bytes) / 1048576.0);
  if (!ok) {
    ++saves_failed_;
    reportProblem("gallery: NOT SAVED (" + why + "): " + error);
    setStorageProblem("NOT SAVING visitors' clouds: " + error);
    return;
  }
  if (storage_problem_.rfind("NOT SAVING visitors", 0) == 0) setStorageProblem("");
  gallery_saved_.push_back(save.number);
  uint64_t bytes = 0;
  for (const std::string& path : save.written) {
    std::error_code ec;
    bytes += std::filesystem::file_size(path, ec);
  }
  std::fprintf(
      stderr, "cloudbrush kiosk: gallery: %s saved as %06ld (%zu files, %.1f MB, %.0f ms)%s%s\n",
      why.c_str(), save.number, save.written.size(), double(bytes) / 1048576.0,
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started).count(),
      save.note.empty() ? "" : "; ", save.note.c_str());
  for (long n : save.cleanup.removed_for_quota)
    std::fprintf(stderr, "cloudbrush kiosk: gallery %06ld deleted (over the quota)\n", n);
  for (long n : save.cleanup.removed_for_age)
    std::fprintf(stderr, "cloudbrush kiosk: gallery %06ld deleted (too old)\n", n);
  saved_notice_ = setup_.texts.format("saved_notice", {{"number", std::to_string(save.number)}});
  saved_notice_until_ns_ = clock_.nowNs() + 6'000'000'000;
}

void KioskScreen::stopping() {
  const bool paused_visit =
      (state_ == State::kOperator || state_ == State::kCalibrate) &&
      (before_operator_ == State::kVisitor || before_operator_ == State::kReconnect);
  if (visiting() || paused_visit) keepFinishedCloud("the kiosk stopped");
  if (visitor_) visitor_->recordTo(nullptr, clock_.nowNs());
  closeJournal();
}

void KioskScreen::endVisit(int64_t now, const std::string& why) {
  keepFinishedCloud(why);
  if (visitor_) visitor_->recordTo(nullptr, now);
  closeJournal();
  // The next visitor's session is made in the loop iteration after the attract loop's first
  // frame (update()), not here: the attract loop's fresh session and the visitor's are each a
  // 256³ allocation, and together with the full volume upload of that frame they stalled one
  // iteration for seconds on a loaded machine (the watchdog pings between iterations).
  next_visitor_pending_ = true;
  attract_shown_ = false;
  ++idle_resets_;
  std::fprintf(stderr,
               "cloudbrush kiosk: idle reset (%s): the sky is cleared; the attract loop resumes\n",
               why.c_str());
  cleanUpOldData();
  notice_.clear();
  attract_.restart();
  setState(State::kAttract);
}

void KioskScreen::onPenSamples(const std::vector<PenSample>& samples) {
  const int64_t now = clock_.nowNs();
  if (pen_) {
    const int connection = int(pen_->connection());
    if (connection != last_connection_) {
      const bool was_connected = last_connection_ == int(PenConnection::kConnected);
      last_connection_ = connection;
      const bool connected = pen_->connection() == PenConnection::kConnected;
      if (state_ == State::kVisitor && was_connected && !connected &&
          pen_->connection() != PenConnection::kFinished)
        setState(State::kReconnect);
      else if (state_ == State::kReconnect && connected)
        reconnected_ns_ = now;  // the painting again with the pen's first sample (below)
      else if ((state_ == State::kOperator || state_ == State::kCalibrate) &&
               before_operator_ == State::kVisitor && !connected && was_connected)
        before_operator_ = State::kReconnect;
      awaiting_first_sample_ = connected;
      if (!connected) reconnected_ns_ = -1;
      if (connected)  // for the hotplug check: when the loop found the (re)connected pen
        std::fprintf(stderr, "cloudbrush kiosk: pen: connected, found by the loop at %.6f s\n",
                     double(MonotonicClock().nowNs()) / 1e9);
    }
  }
  // The tablet is back: the painting returns with the pen's first sample, or after a second
  // without one (the pen lies away from the tablet). Drawn at once, the painting's next frame
  // (often a full-resolution one) would hold that first sample back: 3-6 s under TCG.
  if (state_ == State::kReconnect && reconnected_ns_ >= 0 &&
      (!samples.empty() || double(now - reconnected_ns_) / 1e9 >= kReconnectWaitForSampleS)) {
    reconnected_ns_ = -1;
    setState(State::kVisitor);
  }
  if (awaiting_first_sample_ && !samples.empty()) {
    // For the log and the hotplug check (tests/hil/kms): how long a (re)connected pen took to
    // reach the screen that is showing.
    awaiting_first_sample_ = false;
    first_sample_frame_pending_ = true;
    std::fprintf(stderr,
                 "cloudbrush kiosk: pen: first sample since it connected (event at %.6f s) "
                 "reached the %s screen at %.6f s (monotonic)\n",
                 double(samples.front().t_ns) / 1e9, stateName(state_), double(now) / 1e9);
  }
  switch (state_) {
    case State::kAttract: {
      size_t first = 0;
      while (first < samples.size() && !samples[first].in_proximity) ++first;
      if (first == samples.size()) return;
      beginVisit(now);  // the first pen proximity: the visitor's at once
      paint_.onPenSamples(std::vector<PenSample>(samples.begin() + long(first), samples.end()));
      return;
    }
    case State::kVisitor:
    case State::kReconnect:
      for (const PenSample& s : samples)
        if (s.in_proximity) {
          input(now);
          break;
        }
      paint_.onPenSamples(samples);
      return;
    case State::kOperator:
      return;  // the pen does nothing while the operator panel is open
    case State::kCalibrate:
      calibration_->onPenSamples(samples);
      return;
  }
}

bool KioskScreen::onKey(const DisplayEvent& event, int64_t t_ns) {
  // Calibrating: every key becomes the flow's command (Esc cancels, Space accepts).
  if (state_ == State::kCalibrate) return false;
  if (state_ == State::kOperator) {
    panel_.onKey(event, t_ns);
    runOperatorActions(t_ns);
    if (!panel_.isOpen()) {
      input(t_ns);
      setState(before_operator_);
    }
    return true;
  }
  const uint32_t mods = DisplayEvent::kCtrl | DisplayEvent::kAlt | DisplayEvent::kShift;
  if (lowerLetter(event.keysym) == lowerLetter(operator_keys_.keysym) &&
      (event.modifiers & mods) == (operator_keys_.modifiers & mods)) {
    before_operator_ = state_;
    panel_.askPin();
    setState(State::kOperator);
    logOperator("pin-asked (operator key combination typed)");
    return true;
  }
  if (isModifierKey(event.keysym)) return true;
  if (state_ == State::kAttract) {
    beginVisit(t_ns);  // any key hands over; the key itself only wakes the painter
    return true;
  }
  input(t_ns);
  return false;
}

void KioskScreen::onCommand(Command command, int64_t t_ns) {
  input(t_ns);
  if (state_ == State::kCalibrate) return calibration_->onCommand(command, t_ns);
  if (state_ == State::kVisitor) paint_.onCommand(command, t_ns);
}

void KioskScreen::onPointer(const DisplayEvent& event) {
  const int64_t now = clock_.nowNs();
  if (state_ == State::kOperator || state_ == State::kCalibrate) return;
  if (state_ == State::kAttract) beginVisit(now);
  input(now);
  paint_.onPointer(event);
}

void KioskScreen::onResize(int width, int height) {
  paint_.onResize(width, height);
  if (calibration_) calibration_->onResize(width, height);
}

void KioskScreen::logOperator(const std::string& action) {
  std::string error;
  if (!operator_log_.write(action, &error))
    std::fprintf(stderr, "cloudbrush kiosk: operator log: %s\n", error.c_str());
}

void KioskScreen::startCalibration(int64_t now, bool pressure) {
  // As `cloudbrush calibrate` does, with the kiosk's data dir as the state dir: the profile goes
  // to <data dir>/profiles/ (where the painter looks it up) and the session's record beside it.
  const std::string record = setup_.data_dir + "/calibration-" + utcStamp() + ".cbj";
  calibration_record_ = std::make_unique<JournalWriter>();
  if (!calibration_record_->open(record)) {
    std::fprintf(stderr, "cloudbrush kiosk: calibration record %s (continuing without one)\n",
                 calibration_record_->error().c_str());
    calibration_record_.reset();
  }
  CalibrateFlowOptions options;
  calibrating_pressure_ = pressure;
  if (pressure) options.task = CalibrateFlowOptions::Task::kPressure;
  options.config_dir = setup_.config_dir;
  options.state_dir = setup_.data_dir;
  options.journal = calibration_record_.get();
  options.end_loop_when_done = false;
  options.esc_quits = false;
  options.esc_returns_to = "the operator panel";
  options.log = [](const std::string& line) {
    std::fprintf(stderr, "cloudbrush kiosk: calibrate: %s\n", line.c_str());
  };
  calibration_ =
      std::make_unique<CalibrateFlowScreen>(pen_, display_.width(), display_.height(), options);
  logOperator(
      std::string(OperatorPanelScreen::actionName(pressure ? OperatorActionKind::kCalibratePressure
                                                           : OperatorActionKind::kCalibrate)) +
      " started" + (calibration_record_ ? " (record " + record + ")" : ""));
  input(now);
  setState(State::kCalibrate);
}

void KioskScreen::finishCalibration(int64_t now) {
  const CalibrateOutcome outcome = *calibration_->outcome();
  calibration_.reset();
  // Its programs are deleted while the last one it drew with is still in use; the panel's text
  // would restore that (now invalid) program after drawing, a GL error. Nothing is in use now.
  glUseProgram(0);
  if (calibration_record_) calibration_record_->close();
  calibration_record_.reset();
  const std::string name =
      OperatorPanelScreen::actionName(calibrating_pressure_ ? OperatorActionKind::kCalibratePressure
                                                            : OperatorActionKind::kCalibrate);
  switch (outcome.kind) {
    case CalibrateOutcome::Kind::kSaved: {
      const CalibrationProfile& p = outcome.fit->profile;
      char fit[160];
      std::snprintf(fit, sizeof fit, "%s, %d points, rms %.2f px, max %.2f px",
                    pointFitKindName(p.fit_kind), p.fit_points, p.fit_rms_px, p.fit_max_px);
      // The painter selects the new profile now (journalled in the visitor's session); a pen
      // that is not connected gets it when it connects.
      const bool applied = paint_.reselectCalibration();
      logOperator(name + " saved " + outcome.saved_path + " (" + fit + ")");
      message_ = "calibration saved (" + std::string(fit) + ")\nto " + outcome.saved_path +
                 (applied ? "; the pen uses it now" : "; the pen uses it when it connects");
      break;
    }
    case CalibrateOutcome::Kind::kPressureRange: {
      const PressureRange range = *outcome.pressure.range;
      const std::string path = setup_.data_dir + "/pressure_range.toml";
      std::string error;
      char fit[160];
      std::snprintf(fit, sizeof fit, "lo %.3f, hi %.3f; light press %.3f, firm press %.3f",
                    double(range.lo), double(range.hi), double(outcome.pressure.light),
                    double(outcome.pressure.firm));
      if (!writeFileAtomically(path, pressureRangeToToml(range), &error)) {
        logOperator(name + " FAILED: " + error);
        message_ = "pressure calibration FAILED: " + error;
        break;
      }
      pressure_range_ = range;
      // The visitor's session takes it now (journalled); every later visitor's from the start.
      bool applied = false;
      if (visitor_)
        applied = visitor_->apply(ui::SetPressureRange{range.lo, range.hi}, now, &error);
      logOperator(name + " saved " + path + " (" + fit + ")");
      message_ = "pressure range saved (" + std::string(fit) + ")\nto " + path +
                 (applied ? "; the pen uses it now" : "; visitors' pens use it");
      break;
    }
    case CalibrateOutcome::Kind::kCancelled:
      logOperator(name + " cancelled (nothing saved)");
      message_ = calibrating_pressure_
                     ? "pressure calibration cancelled: nothing saved, the range stays"
                     : "calibration cancelled: nothing saved, the pen keeps its calibration";
      break;
    case CalibrateOutcome::Kind::kFailed:
      logOperator(name + " FAILED: " + outcome.message);
      message_ = "calibration FAILED: " + outcome.message;
      break;
  }
  panel_.shownAgain(now);
  input(now);
  setState(State::kOperator);
}

void KioskScreen::runOperatorActions(int64_t now) {
  KioskConfig& c = setup_.config;
  for (const OperatorAction& action : panel_.takeActions()) {
    const char* name = OperatorPanelScreen::actionName(action.kind);
    char text[256];
    switch (action.kind) {
      case OperatorActionKind::kOpened:
      case OperatorActionKind::kClosed:
      case OperatorActionKind::kPinSet:
        logOperator(name);
        break;
      case OperatorActionKind::kWrongPin:
        std::snprintf(text, sizeof text, "%s (%d in a row)", name, int(action.value));
        logOperator(text);
        break;
      case OperatorActionKind::kLockedOut:
        std::snprintf(text, sizeof text, "%s for %.0f s", name, action.value);
        logOperator(text);
        break;
      case OperatorActionKind::kIdleSeconds:
        c.idle_seconds = action.value;
        std::snprintf(text, sizeof text, "%s %.0f", name, c.idle_seconds);
        logOperator(text);
        message_ = "idle time now " + std::to_string(long(c.idle_seconds)) + " s";
        break;
      case OperatorActionKind::kWarningSeconds:
        c.warning_seconds = action.value;
        std::snprintf(text, sizeof text, "%s %.0f", name, c.warning_seconds);
        logOperator(text);
        message_ = "countdown now " + std::to_string(long(c.warning_seconds)) + " s";
        break;
      case OperatorActionKind::kToggleGallery:
        c.gallery_enabled = !c.gallery_enabled;
        logOperator(std::string(name) + (c.gallery_enabled ? " on" : " off"));
        message_ = std::string("gallery ") + (c.gallery_enabled ? "on" : "off");
        updateTexts();
        break;
      case OperatorActionKind::kExportCloud: {
        if (!visitor_ || !paint_.hasPaint()) {
          message_ = "export: the current visitor has painted nothing yet";
          logOperator(std::string(name) + " (nothing to export)");
          break;
        }
        const std::string dir = setup_.data_dir + "/exports/" + utcStamp();
        std::vector<std::string> written;
        std::string note, error;
        const bool ok = exportCloudFiles(renderer_, visitor_->volume(), paint_.shownCamera(),
                                         visitor_->light(), setup_.render, display_.width(),
                                         display_.height(), dir, &written, &note, &error);
        glBindFramebuffer(GL_FRAMEBUFFER, display_.framebuffer());
        glViewport(0, 0, display_.width(), display_.height());
        message_ = ok ? "exported " + std::to_string(written.size()) + " files to " + dir
                      : "export FAILED: " + error;
        logOperator(std::string(name) + " " + (ok ? dir : "FAILED: " + error));
        break;
      }
      case OperatorActionKind::kCalibrate:
      case OperatorActionKind::kCalibratePressure:
        startCalibration(now, action.kind == OperatorActionKind::kCalibratePressure);
        return;  // the keys after C or P are the calibration's
      case OperatorActionKind::kShutdown:
        logOperator(name);
        quit_ = "operator shutdown";
        break;
    }
  }
}

std::string KioskScreen::update(const FrameContext& frame) {
  const int64_t now = clock_.nowNs();
  checkStorage(now);
  if (journal_ && !journal_failed_ && !journal_->error().empty()) {
    // The visitor paints on; what was written stays a readable journal up to its last record.
    journal_failed_ = true;
    ++saves_failed_;
    reportProblem("journal: " + journal_->path() + ": " + journal_->error());
    setStorageProblem("NOT SAVING journals: " + journal_->error());
  }
  switch (state_) {
    case State::kCalibrate:
      calibration_->update(frame);
      if (calibration_->stage() == CalibrateFlowScreen::Stage::kDone) {
        finishCalibration(now);
        return update(frame);  // the panel, with the result
      }
      break;
    case State::kOperator: {
      panel_.update(frame);
      runOperatorActions(now);
      if (!panel_.isOpen()) {
        input(now);
        setState(before_operator_);
      }
      OperatorPanelValues values;
      values.idle_seconds = setup_.config.idle_seconds;
      values.warning_seconds = setup_.config.warning_seconds;
      values.gallery_enabled = setup_.config.gallery_enabled;
      values.gallery_entries = long(gallery_.entries().size());
      values.data_dir = setup_.data_dir;
      values.storage_ok = storage_problem_.empty();
      values.storage = values.storage_ok ? "ok, " + storageSummary()
                                         : storage_problem_ + " (" + storageSummary() + ")";
      const KioskCounts kiosk_counts = counts();  // what health.json and the metrics carry
      values.gallery_saved = kiosk_counts.gallery_saved;
      values.saves_failed = kiosk_counts.saves_failed;
      if (pressure_range_) {
        char range[64];
        std::snprintf(range, sizeof range, "%.3f..%.3f", double(pressure_range_->lo),
                      double(pressure_range_->hi));
        values.pressure_range = range;
      }
      values.message = message_;
      panel_.setValues(values);
      break;
    }
    case State::kAttract:
      // The next visitor's session, one loop iteration after the reset's (see endVisit).
      if (next_visitor_pending_ && attract_shown_) prepareVisitor();
      attract_.update(frame);
      break;
    case State::kVisitor:
    case State::kReconnect: {
      const double idle = double(now - last_input_ns_) / 1e9;
      const double left = setup_.config.idle_seconds - idle;
      if (left <= 0.0) {
        endVisit(now, "idle");
        attract_.update(frame);
        break;
      }
      if (left <= setup_.config.warning_seconds && paint_.hasPaint())
        notice_ =
            setup_.texts.format("countdown", {{"seconds", std::to_string(int(std::ceil(left)))}});
      else if (now < saved_notice_until_ns_)
        notice_ = saved_notice_;
      else
        notice_.clear();
      const std::string quit = paint_.update(frame);
      if (!quit.empty()) return quit;
      break;
    }
  }
  return quit_;
}

bool KioskScreen::needsFrame() const {
  switch (state_) {
    case State::kVisitor:
      return paint_.needsFrame() || !notice_.empty();
    case State::kReconnect:
      // Drawn when shown and when the pen's status changes: meanwhile the loop polls the pen
      // every few milliseconds and the replug shows at once.
      return !reconnect_drawn_ ||
             *reconnect_drawn_ != (pen_ ? pen_->statusMessage() : std::string());
    default:
      return true;
  }
}

bool KioskScreen::draw(FrameContext& frame, std::string* error) {
  if (!ui_ready_ && !ui_failed_) {
    ui_.addGlyphs(setup_.texts.allText());
    std::string ui_error;
    if (ui_.init(&ui_error)) {
      ui_ready_ = true;
    } else {
      ui_failed_ = true;
      std::fprintf(stderr, "cloudbrush kiosk: visitor texts cannot be drawn: %s\n",
                   ui_error.c_str());
    }
  }
  switch (state_) {
    case State::kAttract:
      return attract_.draw(frame, error);
    case State::kOperator:
      return panel_.draw(frame, error);
    case State::kCalibrate:
      return calibration_->draw(frame, error);
    case State::kReconnect:
      // The painting as it was (no refinement while the pen is away), the message over it.
      if (!paint_.drawLastScene(frame) && !paint_.draw(frame, error)) return false;
      // The pen's status (its driver's words) goes to the log, not to the visitor.
      if (!reconnect_drawn_ && pen_)
        std::fprintf(stderr, "cloudbrush kiosk: reconnect the pen: %s\n",
                     pen_->statusMessage().c_str());
      reconnect_drawn_ = pen_ ? pen_->statusMessage() : std::string();
      reconnect_.setTexts(setup_.texts.text("reconnect_title"), setup_.texts.text("reconnect_hint"),
                          "");
      return reconnect_.draw(frame, error);
    case State::kVisitor:
      if (!paint_.draw(frame, error)) return false;
      if (!notice_.empty()) {
        const float h = float(frame.height);
        glBindFramebuffer(GL_FRAMEBUFFER, display_.framebuffer());
        glViewport(0, 0, frame.width, frame.height);
        ui_.drawLabels(frame.width, frame.height,
                       {{0.5f * float(frame.width), 0.12f * h, notice_, 0.04f * h, 0xffd266ffu,
                         true, 0x000000ccu}});
      }
      return true;
  }
  return true;
}

void KioskScreen::presented(const FrameContext& frame, double frame_ms) {
  if (first_sample_frame_pending_) {
    // The frame drawn after it: what the visitor sees answer the pen.
    first_sample_frame_pending_ = false;
    std::fprintf(stderr,
                 "cloudbrush kiosk: pen: the first frame after that sample (the %s screen) was "
                 "presented at %.6f s (monotonic)\n",
                 stateName(state_), double(MonotonicClock().nowNs()) / 1e9);
  }
  if (state_ == State::kVisitor) paint_.presented(frame, frame_ms);
  if (state_ == State::kAttract) {
    attract_.presented(frame, frame_ms);
    attract_shown_ = true;
  }
  if (state_ == State::kCalibrate) calibration_->presented(frame, frame_ms);
}

}  // namespace cb
