#include "app/shell/study/study_run_screen.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <utility>

#include "app/render/image_io.h"
#include "app/scene/paint_camera.h"
#include "app/shell/painter/paint_screen.h"
#include "app/shell/ui_overlay.h"
#include "app/study/reference_picture.h"
#include "app/study/study_marker_text.h"
#include "app/study/study_sync_markers.h"
#include "app/study/utf8_text.h"
#include "calibration/profile_store.h"
#include "drivers/core/clock.h"
#include "drivers/core/pen_source.h"

namespace cb {
namespace {

PaintLoopOptions paintOptionsFor(PaintLoopOptions options, const std::string& folder,
                                 std::function<float(int, int)> foot_height) {
  options.orbit_degrees_per_second = 0.0f;  // a study paints from the start: no attract orbit
  // The painter's Save writes into the session folder (withdrawn and exported with it), never
  // into the state dir, where no withdrawal of this participant would find it.
  options.save_dir = folder + "/saved";
  // A save's answer and the first screen's hint in the canvas, clear of the runner's panel.
  options.message_area = kStudyPanelLeft;
  // The hint above the foot line that says what the page waits for (drawn over the painter).
  options.message_bottom = std::move(foot_height);
  options.visitor_mode = false;
  options.max_frames = 0;
  options.max_seconds = 0.0;
  options.initial_keys.clear();
  return options;
}

bool sameView(const Camera& a, const Camera& b) {
  return a.eye == b.eye && a.target == b.target && a.up == b.up && a.fov_y_deg == b.fov_y_deg;
}

const char* presetWord(Command command) {
  switch (command) {
    case Command::kResetCamera:
      return "reset";
    case Command::kViewTop:
      return "top";
    case Command::kViewFront:
      return "front";
    case Command::kViewLeft:
      return "left";
    case Command::kViewPerspective:
      return "perspective";
    default:
      return nullptr;
  }
}

}  // namespace

StudyRunScreen::StudyRunScreen(Display& display, VolumeRenderer& renderer, PaintSession& session,
                               PenSource* pen, JournalWriter* journal, StudyRunState& state,
                               const StudyRunOptions& options)
    : display_(display),
      renderer_(renderer),
      session_(session),
      pen_(pen),
      journal_(journal),
      state_(state),
      options_(options),
      task_files_(options.folder),
      paint_(std::make_unique<PaintScreen>(
          display, renderer, session.volume(), session.light(),
          paintOptionsFor(options.paint, options.folder, [this](int w, int h) {
            return studyFootHeight(state_, pageInput(), w, h);
          }))) {
  if (options.replay_view) {
    std::string error;
    if (!paint_->showReplay(&session, &error)) problem("replay: " + error);
  } else {
    paint_->attachPen(pen, &session);
  }
  paint_->setSaveWords([this](const std::string&) { return saveWords(); },
                       "您的云已保存任务教程自由绘画第次（），。");
  now_ns_ = options.resumed ? options.start_ns : options.info.anchor_monotonic_ns;
  circles_shown_ = options.paint.show_circles_overlay;
  last_stage_ = state_.stage();
  last_task_ = state_.position().order;
  seen_.strokes_mapped = session_.strokesMapped();
  seen_.undoable = session_.history().undoable();
  seen_.brush = session_.selectedBrush();
  flushRecords();
  if (options.resumed) {
    // Carry on where the journal ends: the task's picture, its setup when the journal lost it,
    // and the closing page's timer.
    const Volume& v = session_.volume();
    cloud_empty_ = !v.hasDensity();
    empty_checked_generation_ = v.generation();
    strokes_in_cloud_ = cloud_empty_ ? 0 : int64_t(session_.strokesMapped());
    if (state_.stage() == StudyStageKind::kTask) {
      if (options.set_up_stage) setUpTask(now_ns_);
      std::string error;
      if (!loadReferenceImage(&error)) problem("reference image: " + error);
    }
    if (state_.done()) done_since_ = now_ns_;
    // The tutorial step's counters as the journal last had them.
    if (state_.stage() == StudyStageKind::kTutorial) {
      last_step_ = state_.tutorialStep();
      restoreStepProgress(state_.restoredStepProgress());
    }
    if (options.last_mapped && !isPaintingStage(state_.stage())) {
      // A tap under way on a form: the pen is down on its target.
      pen_events_.derive(*options.last_mapped, &events_);
      for (const PenEvent& event : events_)
        if (event.kind == PenEvent::Kind::kDown) tap(event.x, event.y, true, now_ns_);
      events_.clear();
    }
  }
  writeAnswers();
  writeSessionJson();
}

StudyRunScreen::~StudyRunScreen() = default;

void StudyRunScreen::problem(const std::string& text) {
  problems_.push_back(text);
  std::fprintf(stderr, "cloudbrush study: %s\n", text.c_str());
}

void StudyRunScreen::flushRecords() {
  if (options_.replay_view) return;  // the journal has them (and restore() expects them)
  for (const StudyRunRecord& r : state_.takeRecords()) {
    std::fprintf(stderr, "cloudbrush study: %s\n", r.text.c_str());
    if (journal_ && !journal_->append(JournalRecordType::kMarker, r.t_ns, r.text))
      problem("journal: " + journal_->error());
    if (r.text.rfind("study.answer", 0) == 0) writeAnswers();
    // Session, stage, task and answer events also as sync markers (journal and --sync-udp;
    // drivers/core/JOURNAL.md §10), sent as the record is made.
    if (const std::optional<StudySyncMarker> sync = studySyncMarker(r.text))
      session_.markSync(sync->kind, sync->label, r.t_ns);
  }
}

void StudyRunScreen::writeAnswers() {
  if (options_.replay_view) return;
  std::string error;
  if (state_.declined()) {
    // Declined: no answer files (a row of NAs would read as a participant who answered nothing).
    std::error_code ec;
    bool removed = false;
    for (const char* name : {"/questionnaire.csv", "/demographics.csv"})
      removed = std::filesystem::remove(options_.folder + name, ec) || removed;
    if (removed && !syncFolderOf(options_.folder + "/session.json", &error)) problem(error);
    return;
  }
  if (!writeFileAtomically(options_.folder + "/questionnaire.csv", state_.questionnaireCsv(),
                           &error))
    fileNotWritten(error);
  if (!writeFileAtomically(options_.folder + "/demographics.csv", state_.demographicsCsv(), &error))
    fileNotWritten(error);
}

void StudyRunScreen::fileNotWritten(const std::string& error) {
  // Written again each second until it works (watchStorage); one problem per outage.
  if (!files_pending_ && !storage_.failing()) problem(error);
  files_pending_ = true;
  file_error_ = error;
}

void StudyRunScreen::watchStorage() {
  if (options_.replay_view) return;
  if (files_pending_ && now_ns_ >= files_retry_ns_) {
    files_pending_ = false;
    files_retry_ns_ = now_ns_ + 1'000'000'000;
    writeAnswers();
    retryTaskFiles();
    writeSessionJson();
  }
  const bool journal_failing = journal_ && journal_->failing();
  const std::string error = journal_failing ? "journal: " + journal_->error() : file_error_;
  const int64_t unix_now = std::chrono::duration_cast<std::chrono::nanoseconds>(
                               std::chrono::system_clock::now().time_since_epoch())
                               .count();
  if (!storage_.observe(journal_failing || files_pending_, error, unix_now)) return;
  if (storage_.failing())
    problem("storage: " + error + " (kept in memory; written when the disk has room again)");
  else
    std::fprintf(stderr, "cloudbrush study: storage: writing again; nothing was lost\n");
  writeSessionJson();  // the outage in session.json (written again until it works)
}

void StudyRunScreen::retryTaskFiles() {
  if (!task_files_.pending()) return;
  std::string error;
  const std::vector<std::string> written = task_files_.retry(&error);
  if (!written.empty()) {
    // Journalled (the screen's record, as step-progress is): when each late file reached disk.
    std::string list;
    for (const std::string& file : written) list += (list.empty() ? "" : ",") + file;
    const std::string text = "study.files-written files=" + studyMarkerValue(list);
    std::fprintf(stderr, "cloudbrush study: %s\n", text.c_str());
    if (journal_ && !journal_->append(JournalRecordType::kMarker, now_ns_, text))
      problem("journal: " + journal_->error());
  }
  if (task_files_.pending()) fileNotWritten(error);
}

void StudyRunScreen::writeSessionJson() {
  if (options_.replay_view) return;
  StudySessionInfo info = options_.info;
  info.status = !state_.done()      ? "running"
                : state_.declined() ? "declined"
                : state_.aborted()  ? "aborted"
                                    : "completed";
  info.abort_reason = state_.abortReason();
  // The pen this run gave the session (it may have finished since: a recording played out).
  if (pen_ && (pen_->connection() == PenConnection::kConnected || device_selected_)) {
    info.device = pen_->deviceInfo();
    info.device_serial = pen_->serialNumber(&info.device_serial_note);
  }
  info.calibration_toml = formatCalibrationProfile(session_.calibration());
  info.stages_completed = state_.stagesCompleted();
  info.storage_json = storage_.json();
  std::string error;
  if (!writeFileAtomically(options_.folder + "/session.json", formatStudySessionJson(info), &error))
    fileNotWritten(error);
}

void StudyRunScreen::selectCalibration() {
  const PenDeviceInfo& device = pen_->deviceInfo();
  device_selected_ = true;
  session_.setDevice(device, now_ns_);
  ProfileSelection selection =
      selectProfile(device, tool_serial_, options_.paint.config_dir, options_.paint.state_dir);
  for (const std::string& message : selection.messages)
    std::fprintf(stderr, "cloudbrush study: calibration: %s\n", message.c_str());
  session_.setCalibration(selection.profile, now_ns_);
  writeSessionJson();
}

bool StudyRunScreen::loadReferenceImage(std::string* error) {
  const StudyTask* task = state_.task();
  image_aspect_ = 0.0f;
  if (!task || task->image.empty()) return true;
  if (image_path_ == task->image && image_.texture()) {
    image_aspect_ = float(image_.width()) / float(image_.height());
    return true;
  }
  try {
    const ImageRgba8 picture = referencePictureForDisplay(readPng(task->image));
    if (!image_.create(picture.width, picture.height, RenderTarget::Format::kRgba8, error))
      return false;
    glTextureSubImage2D(image_.texture(), 0, 0, 0, picture.width, picture.height, GL_RGBA,
                        GL_UNSIGNED_BYTE, picture.pixels.data());
    image_path_ = task->image;
    image_aspect_ = float(picture.width) / float(picture.height);
    return true;
  } catch (const std::exception& e) {
    *error = e.what();
    return false;
  }
}

void StudyRunScreen::setUpTask(int64_t t_ns) {
  // Each task starts from an empty sky in Paint mode at the painter's starting view (§7.5: one
  // cloud per picture).
  std::string error;
  if (session_.history().canUndo() || !cloud_empty_) session_.apply(ui::DeleteAll{}, t_ns, &error);
  session_.apply(ui::SetMode{Mode::kPaint}, t_ns, &error);
  session_.apply(ui::SetCamera{initialPaintCamera(session_.settings())}, t_ns, &error);
}

void StudyRunScreen::enterStage(int64_t t_ns) {
  last_stage_ = state_.stage();
  last_task_ = state_.position().order;
  last_step_ = -1;
  typed_.clear();
  message_.clear();
  keyboard_page_ = kKeyboardLower;
  pressed_.reset();
  done_asked_ = false;
  saves_in_stage_ = 0;
  if (state_.stage() == StudyStageKind::kTask) {
    if (!options_.replay_view) setUpTask(t_ns);  // a replay has the setup in its journal
    std::string error;
    if (!loadReferenceImage(&error)) problem("reference image: " + error);
  }
  if (state_.done()) {
    done_since_ = t_ns;
    writeAnswers();
    if (journal_ && !journal_->sync()) problem("journal: " + journal_->error());
  }
  writeSessionJson();
}

void StudyRunScreen::afterStateChange(int64_t t_ns) {
  flushRecords();
  if (state_.stage() != last_stage_ || state_.position().order != last_task_) enterStage(t_ns);
  if (state_.stage() == StudyStageKind::kTutorial && state_.tutorialStep() != last_step_) {
    last_step_ = state_.tutorialStep();
    strokes_in_step_ = brush_changes_in_step_ = erasures_in_step_ = undos_in_step_ =
        saves_in_step_ = 0;
    step_progress_.clear();
  }
}

void StudyRunScreen::saveTask(int64_t t_ns) {
  const StudyTask* task = state_.task();
  std::vector<std::string> saved;
  if (task) {
    const auto has = [&](TaskSaveKind kind) {
      return std::find(task->save.begin(), task->save.end(), kind) != task->save.end();
    };
    if (has(TaskSaveKind::kJournal) && journal_) {
      if (journal_->sync())
        saved.push_back("session.cbj");
      else
        problem("journal: " + journal_->error());
    }
    // Files that cannot be written now are kept and written again each second (watchStorage).
    std::string note, error;
    if (has(TaskSaveKind::kVolumeVdb) || has(TaskSaveKind::kVolumeRaw)) {
      if (!task_files_.writeVolume(task->id, session_.volume(), &saved, &note, &error))
        fileNotWritten("task " + task->id + ": " + error);
      if (!note.empty()) problem(note);
    }
    if (has(TaskSaveKind::kRenderExr) || has(TaskSaveKind::kRenderPng)) {
      ImageRgbaF frame;
      if (!renderTaskFrame(&frame, &error))
        problem("task " + task->id + ": " + error);
      else if (!task_files_.writeFrame(task->id, frame, &saved, &error))
        fileNotWritten("task " + task->id + ": " + error);
    }
  }
  // The next stage begins when the participant sees it: after the saving (its clock starts
  // then, and its sync marker carries that time).
  if (options_.paint.clock) now_ns_ = std::max(t_ns, options_.paint.clock->nowNs());
  std::vector<std::string> pending;
  if (task)
    for (const std::string& file : task_files_.pendingFiles())
      if (file.rfind("tasks/" + task->id + ".", 0) == 0) pending.push_back(file);
  // The participant reads it on the next page for a few seconds; the operator in the log.
  saved_task_ = state_.position().order + 1;
  saved_pending_ = !pending.empty();
  saved_until_ns_ = now_ns_ + kSavedNoticeNs;
  std::string files;
  for (const std::string& file : saved) files += (files.empty() ? "" : ", ") + file;
  std::fprintf(stderr, "cloudbrush study: %s (%s): %s%s%s\n",
               studyTaskSavedText(saved_task_, saved_pending_).en.c_str(),
               task ? task->id.c_str() : "-", files.empty() ? "no files" : files.c_str(),
               pending.empty() ? "" : "; waiting for the disk: ",
               pending.empty() ? "" : std::to_string(pending.size()).append(" file(s)").c_str());
  state_.closeStage(now_ns_, saved, pending);
}

void StudyRunScreen::writeTaskSoFar() {
  const StudyTask* task = state_.task();
  const Volume& v = session_.volume();
  if (!task || cloud_empty_ || session_.engine().inStroke() || now_ns_ < so_far_due_ns_ ||
      v.generation() == so_far_generation_)
    return;
  if (std::find(task->save.begin(), task->save.end(), TaskSaveKind::kVolumeVdb) ==
          task->save.end() &&
      std::find(task->save.begin(), task->save.end(), TaskSaveKind::kVolumeRaw) == task->save.end())
    return;
  so_far_generation_ = v.generation();
  so_far_due_ns_ = now_ns_ + kSoFarNs;
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::string> written;
  std::string note, error;
  if (!task_files_.writeVolumeSoFar(task->id, v, &written, &note, &error)) {
    // Not kept: the task's end writes them (and keeps them when the disk still fails).
    std::fprintf(stderr, "cloudbrush study: task %s so far not written: %s\n", task->id.c_str(),
                 error.c_str());
    return;
  }
  std::string files;
  for (const std::string& file : written) files += (files.empty() ? "" : ", ") + file;
  std::fprintf(
      stderr, "cloudbrush study: task %s so far: %s (%.0f ms)\n", task->id.c_str(), files.c_str(),
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
}

std::string StudyRunScreen::saveWords() {
  // The answer to the painter's Save in a study: which stage's cloud, how many saves so far;
  // the folder and file name go to the log only (PaintScreen::saveCloud).
  ++saves_in_stage_;
  const std::string n = std::to_string(saves_in_stage_);
  std::string where_en, where_zh;
  switch (state_.stage()) {
    case StudyStageKind::kTask: {
      const std::string task = std::to_string(state_.position().order + 1);
      where_en = "task " + task, where_zh = "任务 " + task;
      break;
    }
    case StudyStageKind::kTutorial:
      where_en = "tutorial", where_zh = "教程";
      break;
    default:
      where_en = "free drawing", where_zh = "自由绘画";
      break;
  }
  return "Your cloud is saved (" + where_en + ", save " + n + "). / 您的云已保存（" + where_zh +
         "，第 " + n + " 次保存）。";
}

bool StudyRunScreen::renderTaskFrame(ImageRgbaF* frame, std::string* error) {
  // The task-end view, rendered at full resolution into a float target (the values the
  // display shows; render_export.h makes the linear EXR and the PNG).
  const int w = display_.width(), h = display_.height();
  RenderTarget target;
  if (!target.create(w, h, RenderTarget::Format::kRgba32F, error)) return false;
  renderer_.sync(session_.volume(), session_.light());
  RenderOptions options = options_.paint.render;
  options.style = parseRenderStyle(session_.styleName()).value_or(options.style);
  options.scale = 1.0f;
  options.moving = false;
  options.collect_stats = false;
  options.finish = true;
  renderer_.render(session_.camera(), w, h, target.fbo(), options);
  *frame = target.readRgbaF();
  return true;
}

TutorialState StudyRunScreen::tutorialState() const {
  TutorialState s;
  const Volume& v = session_.volume();
  s.words["mode"] = modeName(session_.mode());
  if (!camera_view_.empty()) s.words["camera_view"] = camera_view_;
  s.words["brush"] = brushKindName(session_.selectedBrush());
  s.words["erase_tool"] = eraseToolName(session_.eraseTool());
  const glm::vec3 offset = session_.camera().eye - session_.camera().target;
  const float length = glm::length(offset);
  s.numbers["camera_elevation_deg"] =
      length > 0.0f ? int64_t(std::lround(
                          glm::degrees(std::asin(std::clamp(offset.y / length, -1.0f, 1.0f)))))
                    : 0;
  s.numbers["canvas_altitude"] =
      int64_t(std::lround((session_.canvas().altitude - v.worldMin().y) / v.voxelSize().y));
  s.numbers["strokes"] = strokes_in_cloud_;
  s.numbers["cloud_empty"] = cloud_empty_ ? 1 : 0;
  s.numbers["circles_shown"] = circles_shown_ ? 1 : 0;
  s.numbers["menu_open"] = paint_->menuOpen() ? 1 : 0;
  s.numbers["strokes_in_step"] = strokes_in_step_;
  s.numbers["brush_changes_in_step"] = brush_changes_in_step_;
  s.numbers["erasures_in_step"] = erasures_in_step_;
  s.numbers["undos_in_step"] = undos_in_step_;
  s.numbers["saves_in_step"] = saves_in_step_;
  return s;
}

void StudyRunScreen::observeSession() {
  // Commands tapped on the painter's own menu count like keys.
  const std::vector<Command>& tapped = paint_->tappedCommands();
  for (; seen_.tapped < tapped.size(); ++seen_.tapped) {
    const Command c = tapped[seen_.tapped];
    if (presetWord(c)) preset_pending_ = c;
    if (c == Command::kToggleCircles) circles_shown_ = !circles_shown_;
    if (c == Command::kSave) ++saves_in_step_;
  }
  const Volume& v = session_.volume();
  const bool volume_changed = v.generation() != seen_.generation;
  if (v.generation() != empty_checked_generation_) {
    empty_checked_generation_ = v.generation();
    cloud_empty_ = !v.hasDensity();
    if (cloud_empty_) strokes_in_cloud_ = 0;
  }
  if (session_.strokesMapped() > seen_.strokes_mapped) {
    const int64_t added = session_.strokesMapped() - seen_.strokes_mapped;
    strokes_in_cloud_ += added;
    strokes_in_step_ += added;
  }
  const size_t undoable = session_.history().undoable();
  if (undoable < seen_.undoable) {
    undos_in_step_ += int64_t(seen_.undoable - undoable);
    if (volume_changed) strokes_in_cloud_ = std::max<int64_t>(0, strokes_in_cloud_ - 1);
  } else if (undoable > seen_.undoable && session_.mode() == Mode::kErase && volume_changed) {
    ++erasures_in_step_;  // a rub-out stroke or a vacuum cut
  }
  if (session_.selectedBrush() != seen_.brush) ++brush_changes_in_step_;
  seen_.strokes_mapped = session_.strokesMapped();
  seen_.undoable = undoable;
  seen_.brush = session_.selectedBrush();
  seen_.generation = v.generation();
  // The camera: a preset names the view; any other change (an orbit, a zoom) makes it free.
  if (preset_pending_) {
    camera_view_ = presetWord(*preset_pending_);  // even when the view was already there
  } else if (have_last_camera_ && !sameView(last_camera_, session_.camera())) {
    camera_view_ = "free";
  }
  last_camera_ = session_.camera();
  have_last_camera_ = true;
  preset_pending_.reset();
}

std::string StudyRunScreen::stepProgressText() const {
  std::string text = "study.step-progress step=" + std::to_string(state_.tutorialStep() + 1) +
                     " strokes=" + std::to_string(strokes_in_step_) +
                     " brush_changes=" + std::to_string(brush_changes_in_step_) +
                     " erasures=" + std::to_string(erasures_in_step_) +
                     " undos=" + std::to_string(undos_in_step_) +
                     " saves=" + std::to_string(saves_in_step_) +
                     " circles_shown=" + (circles_shown_ ? "1" : "0");
  if (!camera_view_.empty()) text += " camera_view=" + studyMarkerValue(camera_view_);
  return text;
}

void StudyRunScreen::recordStepProgress() {
  const std::string text = stepProgressText();
  if (text == step_progress_) return;
  const bool first = step_progress_.empty();
  step_progress_ = text;
  // Nothing counted yet in a fresh step: nothing to carry on.
  if (first && strokes_in_step_ == 0 && brush_changes_in_step_ == 0 && erasures_in_step_ == 0 &&
      undos_in_step_ == 0 && saves_in_step_ == 0 && camera_view_.empty() &&
      circles_shown_ == options_.paint.show_circles_overlay)
    return;
  if (journal_ && !journal_->append(JournalRecordType::kMarker, now_ns_, text))
    problem("journal: " + journal_->error());
}

void StudyRunScreen::restoreStepProgress(const std::string& text) {
  if (text.empty()) return;
  const StudyMarkerFields m = parseStudyMarker(text);
  if (m.get("step") != std::to_string(state_.tutorialStep() + 1)) return;  // an earlier step's
  const auto number = [&](const char* key) { return int64_t(std::atoll(m.get(key).c_str())); };
  strokes_in_step_ = number("strokes");
  brush_changes_in_step_ = number("brush_changes");
  erasures_in_step_ = number("erasures");
  undos_in_step_ = number("undos");
  saves_in_step_ = number("saves");
  circles_shown_ = m.get("circles_shown") == "1";
  paint_->showCircles(circles_shown_);
  camera_view_ = m.get("camera_view");
  step_progress_ = text;
}

void StudyRunScreen::onPenSamples(const std::vector<PenSample>& samples) {
  if (!page_drawn_) {
    held_.insert(held_.end(), samples.begin(), samples.end());
    return;
  }
  if (!held_.empty()) {
    std::vector<PenSample> waited = std::move(held_);
    held_.clear();
    waited.insert(waited.end(), samples.begin(), samples.end());
    feedSamples(waited);
    return;
  }
  feedSamples(samples);
}

void StudyRunScreen::feedSamples(const std::vector<PenSample>& samples) {
  if (pen_) {
    const int connection = int(pen_->connection());
    const bool changed = connection != last_connection_;
    last_connection_ = connection;
    if (changed && pen_->connection() != PenConnection::kConnected) device_selected_ = false;
    // The device and its calibration before the pen's first sample: at the connection, or when
    // samples come from a pen already finished again (a recording played out in one poll).
    if ((changed && pen_->connection() == PenConnection::kConnected) ||
        (!samples.empty() && !device_selected_))
      selectCalibration();
  }
  const bool painting = isPaintingStage(state_.stage()) && !state_.paused() && !state_.choosing();
  if (!painting) panel_holds_pen_ = false;
  for (const PenSample& sample : samples) {
    if (painting)
      paintingSample(sample);
    else
      formSample(sample);
  }
}

bool StudyRunScreen::panelTargetAt(float x, float y) const {
  return isPaintingStage(state_.stage()) && page_.hit(x, y) != nullptr;
}

void StudyRunScreen::paintingSample(const PenSample& sample) {
  if (!panel_holds_pen_) {
    paint_->onPenSamples({sample});
    const PaintScreen::PenPoint p = paint_->penPoint();
    panel_holds_pen_ =
        p.in_proximity && !p.down && !session_.engine().inStroke() && panelTargetAt(p.x, p.y);
    return;
  }
  formSample(sample);
  // Back to the painter once the pen is up and away from the targets (or gone).
  if (!pen_events_.down() &&
      (!pen_events_.inProximity() || !panelTargetAt(form_pen_x_, form_pen_y_)))
    panel_holds_pen_ = false;
}

void StudyRunScreen::formSample(const PenSample& sample) {
  // The forms hold the pen: journalled as the UI's capture, so a tap never paints.
  if (!session_.penCaptured() && !pen_events_.down() && !session_.engine().inStroke())
    session_.apply(ui::PenCapture{true}, sample.t_ns);
  const SampleOutcome outcome = session_.feed(sample);
  events_.clear();
  pen_events_.derive(outcome.mapped, &events_);
  form_pen_x_ = float(outcome.mapped.x_px);
  form_pen_y_ = float(outcome.mapped.y_px);
  for (const PenEvent& event : events_) {
    if (event.kind == PenEvent::Kind::kDown) tap(event.x, event.y, true, now_ns_);
    if (event.kind == PenEvent::Kind::kUp) tap(event.x, event.y, false, now_ns_);
  }
}

void StudyRunScreen::tap(float x, float y, bool down, int64_t t_ns) {
  // Before the first frame (a resumed run whose pen is already on the form), the page the
  // participant had in front of them.
  if (page_.targets.empty() && page_.labels.empty())
    page_ = currentPage(display_.width(), display_.height());
  const StudyTarget* target = page_.hit(x, y);
  if (down) {
    if (target)
      pressed_ = *target;
    else
      pressed_.reset();
    return;
  }
  // A tap: down and up on the same target.
  if (target && pressed_ && target->action == pressed_->action &&
      target->value == pressed_->value && target->text == pressed_->text)
    activate(*target, t_ns);
  pressed_.reset();
}

void StudyRunScreen::activate(const StudyTarget& target, int64_t t_ns) {
  const bool free_text = state_.stage() == StudyStageKind::kFreeText;
  switch (target.action) {
    case StudyTargetAction::kAgree:
      state_.agree(t_ns);
      break;
    case StudyTargetAction::kDecline:
      state_.decline(t_ns);
      break;
    case StudyTargetAction::kDone:
      done_asked_ = state_.stage() == StudyStageKind::kTask;
      break;
    case StudyTargetAction::kDoneConfirm:
      done_asked_ = false;
      state_.finishTask(t_ns);
      break;
    case StudyTargetAction::kDoneCancel:
      done_asked_ = false;
      break;
    case StudyTargetAction::kContinue:
      state_.proceed(t_ns);
      break;
    case StudyTargetAction::kAnswer:
      state_.answerItem(target.value, t_ns);
      break;
    case StudyTargetAction::kSkipItem:
      state_.skipItem(t_ns);
      break;
    case StudyTargetAction::kBackItem:
      state_.previousItem(t_ns);
      break;
    case StudyTargetAction::kKey:
      appendTyped(&typed_, target.text, kMaxTypedBytes);
      break;
    case StudyTargetAction::kBackspace:
      eraseLastCharacter(&typed_);
      break;
    case StudyTargetAction::kKeyboardPage:
      keyboard_page_ = keyboard_page_ == target.value ? kKeyboardLower : target.value;
      break;
    case StudyTargetAction::kChoice:
      message_ = state_.answerField(target.text, t_ns);
      break;
    case StudyTargetAction::kOk:
      if (free_text) {
        state_.answerFreeText(typed_, t_ns);
        typed_.clear();
      } else {
        message_ = state_.answerField(typed_, t_ns);
        if (message_.empty()) typed_.clear();
      }
      break;
    case StudyTargetAction::kSkipField:
      if (free_text)
        state_.answerFreeText("", t_ns);
      else
        state_.skipField(t_ns);
      typed_.clear();
      message_.clear();
      break;
    case StudyTargetAction::kReason:
      state_.chooseReason(target.value, t_ns);
      break;
    case StudyTargetAction::kCancel:
      state_.cancelChoice(t_ns);
      break;
  }
  afterStateChange(t_ns);
}

void StudyRunScreen::onCommand(Command command, int64_t t_ns) {
  (void)t_ns;  // the runner keeps to the frame clock, so tests can drive time
  const int64_t t = now_ns_;
  const int digit = command >= Command::kModeCamera && command <= Command::kModeLight
                        ? int(command) - int(Command::kModeCamera) + 1
                        : 0;
  if (command == Command::kOperatorPause || command == Command::kOperatorSkip ||
      command == Command::kOperatorAbort) {
    state_.requestOperator(command == Command::kOperatorPause  ? OperatorAction::kPause
                           : command == Command::kOperatorSkip ? OperatorAction::kSkip
                                                               : OperatorAction::kAbort,
                           t);
  } else if (state_.choosing()) {
    if (digit) state_.chooseReason(digit - 1, t);
    if (command == Command::kQuit) state_.cancelChoice(t);
  } else if (state_.paused() || state_.done()) {
    // only the operator's resume (above) or Esc at the end (the frame loop quits)
  } else if (isPaintingStage(state_.stage())) {
    if (command == Command::kQuit) {
      std::fprintf(stderr,
                   "cloudbrush study: Esc/q do not end a study session: the operator aborts with "
                   "Ctrl+Alt+A\n");
    } else {
      if (presetWord(command)) preset_pending_ = command;
      if (command == Command::kToggleCircles) circles_shown_ = !circles_shown_;
      if (command == Command::kSave) ++saves_in_step_;
      paint_->onCommand(command, t);
    }
  } else if (command == Command::kSpace) {
    if (state_.stage() == StudyStageKind::kConsent)
      state_.agree(t);
    else
      state_.proceed(t);
  } else if (digit && state_.stage() == StudyStageKind::kQuestionnaire) {
    state_.answerItem(digit, t);
  }
  afterStateChange(t);
}

bool StudyRunScreen::atlasHolds(const std::string& text) const {
  for (size_t i = 0; i < text.size();) {
    const auto lead = static_cast<unsigned char>(text[i]);
    const size_t n = lead < 0x80 ? 1 : lead < 0xE0 ? 2 : lead < 0xF0 ? 3 : 4;
    // ASCII and Latin-1 (lead bytes C2, C3) are always in the atlas.
    if (lead > 0xC3 && atlas_text_.find(text.substr(i, n)) == std::string::npos) return false;
    i += n;
  }
  return true;
}

bool StudyRunScreen::onKey(const DisplayEvent& event, int64_t t_ns) {
  (void)t_ns;  // the runner keeps to the frame clock
  const bool text_form = state_.stage() == StudyStageKind::kFreeText ||
                         (state_.stage() == StudyStageKind::kDemographics &&
                          state_.protocol().demographics[size_t(state_.fieldIndex())].kind !=
                              DemographicField::Kind::kChoice);
  if (!text_form || state_.paused() || state_.choosing() || options_.replay_view ||
      (event.modifiers & (DisplayEvent::kCtrl | DisplayEvent::kAlt)))
    return false;
  constexpr uint32_t kBackSpace = 0xff08, kReturn = 0xff0d, kKeypadEnter = 0xff8d;  // X keysyms
  StudyTarget target;
  if (event.keysym == kBackSpace) {
    target.action = StudyTargetAction::kBackspace;
  } else if (event.keysym == kReturn || event.keysym == kKeypadEnter) {
    target.action = StudyTargetAction::kOk;
  } else if (isTypedText(event.text)) {
    target.action = StudyTargetAction::kKey;
    target.text = event.text;
  } else {
    return false;
  }
  activate(target, now_ns_);
  return true;
}

void StudyRunScreen::onPointer(const DisplayEvent& event) {
  if (isPaintingStage(state_.stage()) && !state_.paused() && !state_.choosing()) {
    // A click on the panel's targets is the panel's; everything else the painter's.
    const bool press = event.kind == DisplayEvent::Kind::PointerDown && event.button == 1;
    const bool release =
        event.kind == DisplayEvent::Kind::PointerUp && event.button == 1 && mouse_down_;
    if (!(press && panelTargetAt(event.x, event.y)) && !release) return paint_->onPointer(event);
  }
  if (event.kind == DisplayEvent::Kind::PointerDown && event.button == 1) {
    mouse_down_ = true;
    tap(event.x, event.y, true, now_ns_);
  } else if (event.kind == DisplayEvent::Kind::PointerUp && event.button == 1 && mouse_down_) {
    mouse_down_ = false;
    tap(event.x, event.y, false, now_ns_);
  }
}

void StudyRunScreen::onResize(int width, int height) {
  paint_->onResize(width, height);
}

std::string StudyRunScreen::update(const FrameContext& frame) {
  now_ns_ = frame.now_ns;
  if (options_.replay_view) {
    // The replay moves the session and the state; only what the screen shows follows them.
    if (isPaintingStage(state_.stage())) {
      paint_->update(frame);
      observeSession();
    }
    afterStateChange(now_ns_);
    return "";
  }
  state_.tick(now_ns_);
  flushRecords();  // a task's end goes out now, not after its files are saved
  if (isPaintingStage(state_.stage())) {
    paint_->update(frame);  // its timers (a replay's end does not end a study)
    observeSession();
    if (state_.stage() == StudyStageKind::kTutorial) {
      recordStepProgress();
      state_.observeTutorial(tutorialState(), now_ns_);
    }
    if (state_.stage() == StudyStageKind::kTask && !state_.closing()) writeTaskSoFar();
    if (state_.closing() && !session_.engine().inStroke()) {
      if (state_.stage() == StudyStageKind::kTask)
        saveTask(now_ns_);
      else
        state_.closeStage(now_ns_);
    }
  }
  afterStateChange(now_ns_);
  watchStorage();
  if (state_.done() && done_since_ && double(now_ns_ - *done_since_) / 1e9 >= options_.end_seconds)
    return state_.declined()  ? "consent declined"
           : state_.aborted() ? "study aborted"
                              : "study complete";
  return "";
}

StudyPageInput StudyRunScreen::pageInput() const {
  StudyPageInput input;
  input.typed = typed_;
  input.keyboard_page = keyboard_page_;
  if (!options_.replay_view)
    input.storage_warning =
        storage_.operatorText((journal_ ? journal_->heldBytes() : 0) + task_files_.heldBytes(),
                              std::chrono::duration_cast<std::chrono::nanoseconds>(
                                  std::chrono::system_clock::now().time_since_epoch())
                                  .count(),
                              task_files_.pendingText());
  input.message = message_;
  input.now_ns = now_ns_;
  // Texts measured with the font they are drawn in (an estimate before the first frame).
  if (ui_) input.measure = [ui = ui_.get()](const UiLabel& l, float r[4]) { ui->labelRect(l, r); };
  input.painter_menu_open = isPaintingStage(state_.stage()) && paint_->menuOpen();
  input.done_asked = done_asked_;
  if (now_ns_ < saved_until_ns_) {
    input.saved_task = saved_task_;
    input.saved_pending = saved_pending_;
  }
  input.image_aspect = state_.stage() == StudyStageKind::kTask ? image_aspect_ : 0.0f;
  if (state_.stage() == StudyStageKind::kTutorial) {
    input.check = tutorialStepWords(
        state_.protocol().tutorial[size_t(state_.tutorialStep())].expect, tutorialState());
  }
  return input;
}

StudyPage StudyRunScreen::currentPage(int width, int height) const {
  return buildStudyPage(state_, pageInput(), width, height);
}

bool StudyRunScreen::draw(FrameContext& frame, std::string* error) {
  const int w = frame.width, h = frame.height;
  // The font first: the page, and the painter's hint above its foot line, are laid out from
  // their texts' measured sizes.
  if (ui_ && !atlasHolds(typed_)) {
    // Characters typed beyond the atlas (an input method's Chinese): the atlas is made again
    // with them (once per new character; Latin-1 and the protocol's texts are in it).
    glyphs_ += typed_;
    ui_.reset();
  }
  if (!ui_) {
    ui_ = std::make_unique<UiOverlay>();
    atlas_text_ = studyPageText(state_.protocol()) + glyphs_;
    ui_->addGlyphs(atlas_text_);
    if (!ui_->init(error)) return false;
  }
  if (isPaintingStage(state_.stage())) {
    if (!paint_->draw(frame, error)) return false;
  } else {
    const float black[4] = {0.0f, 0.0f, 0.0f, 1.0f};
    glClearNamedFramebufferfv(display_.framebuffer(), GL_COLOR, 0, black);
  }
  page_ = currentPage(w, h);
  page_drawn_ = true;
  if (!hud_ready_) {
    if (!hud_.init(error)) return false;
    hud_ready_ = true;
  }
  hud_.draw(display_.framebuffer(), w, h, page_.boxes);
  if (image_aspect_ > 0.0f && page_.image[2] > page_.image[0]) {
    // The reference picture, upright (image row 0 is its top; GL rows count from the bottom).
    glBlitNamedFramebuffer(image_.fbo(), display_.framebuffer(), 0, 0, image_.width(),
                           image_.height(), GLint(page_.image[0]), GLint(h - page_.image[1]),
                           GLint(page_.image[2]), GLint(h - page_.image[3]), GL_COLOR_BUFFER_BIT,
                           GL_LINEAR);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, display_.framebuffer());
  glViewport(0, 0, w, h);
  ui_->drawLabels(w, h, page_.labels);
  return true;
}

void StudyRunScreen::presented(const FrameContext& frame, double frame_ms) {
  if (isPaintingStage(state_.stage())) paint_->presented(frame, frame_ms);
}

}  // namespace cb
