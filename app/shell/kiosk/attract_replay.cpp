#include "app/shell/kiosk/attract_replay.h"

#include <algorithm>

namespace cb {
namespace {

AttractKeyframe keyframeOf(const PaintSession& session, int64_t t_ns, size_t records,
                           std::shared_ptr<const Volume> volume) {
  AttractKeyframe k;
  k.t_ns = t_ns;
  k.records = records;
  k.volume = std::move(volume);
  k.camera = session.camera();
  k.light = session.light();
  k.style = session.styleName();
  return k;
}

}  // namespace

AttractReplay::AttractReplay(std::vector<JournalRecord> journal, PaintSessionSettings settings,
                             BrushConfig brush, MappingConfig mapping, Light light,
                             size_t keyframe_budget_bytes)
    : journal_(std::move(journal)), budget_bytes_(keyframe_budget_bytes) {
  // The empty sky the replay starts from, available at once.
  PaintSession empty(settings, brush, mapping);
  empty.setStartingLight(light);
  keyframes_.push_back(keyframeOf(empty, 0, 0, std::make_shared<const Volume>(empty.volume())));
  held_bytes_ = peak_bytes_ = keyframes_.front().volume->memoryBytes();
  if (journal_.empty()) return;
  worker_ = std::thread(
      [this, settings, brush, mapping, light] { run(settings, brush, mapping, light); });
}

AttractReplay::~AttractReplay() {
  stop_ = true;
  if (worker_.joinable()) worker_.join();
}

void AttractReplay::run(PaintSessionSettings settings, BrushConfig brush, MappingConfig mapping,
                        Light light) {
  PaintSession session(settings, brush, mapping);
  session.setQuietMapping(true);
  session.setStartingLight(light);
  uint64_t generation = session.volume().generation();
  std::shared_ptr<const Volume> volume;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    volume = keyframes_.front().volume;
  }
  for (size_t i = 0; i < journal_.size() && !stop_; ++i) {
    const JournalRecord& record = journal_[i];
    std::string error;
    // The Session record made the settings (with the kiosk's grid); everything else applies.
    const bool applied =
        record.type == JournalRecordType::kSession || session.applyRecord(record, nullptr, &error);
    const bool changed_cloud = session.volume().generation() != generation;
    if (changed_cloud) {
      generation = session.volume().generation();
      volume = std::make_shared<const Volume>(session.volume());
    }
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (!applied && problems_.size() < 20)
        problems_.push_back("attract journal record " + std::to_string(i) + ": " + error);
      // Pen samples change what the attract loop shows only when a stroke is mapped; other
      // records (camera, sun, style, ...) may change the view.
      if (changed_cloud || record.type != JournalRecordType::kPenSample)
        keyframes_.push_back(keyframeOf(session, recordTime(i), i + 1, volume));
      if (changed_cloud) {
        held_bytes_ += volume->memoryBytes();
        ++clouds_kept_;
        peak_bytes_ = std::max(peak_bytes_, held_bytes_);
        thinClouds();
      }
      replayed_ = i + 1;
    }
    progressed_.notify_all();
  }
}

void AttractReplay::waitUntilFinished() const {
  std::unique_lock<std::mutex> lock(mutex_);
  progressed_.wait(lock, [this] { return replayed_.load() == journal_.size(); });
}

AttractKeyframe AttractReplay::keyframeAt(size_t records) const {
  std::lock_guard<std::mutex> lock(mutex_);
  size_t k = 0;
  while (k + 1 < keyframes_.size() && keyframes_[k + 1].records <= records) ++k;
  return keyframes_[k];
}

void AttractReplay::thinClouds() {
  while (held_bytes_ > budget_bytes_) {
    // Each distinct cloud's first keyframe, in order (keyframes of one cloud are adjacent).
    std::vector<size_t> first;
    for (size_t k = 0; k < keyframes_.size(); ++k)
      if (k == 0 || keyframes_[k].volume != keyframes_[k - 1].volume) first.push_back(k);
    if (first.size() < 3) return;  // the empty sky and the newest cloud stay
    // The interior cloud whose neighbours lie closest together: dropping it leaves the most
    // even steps.
    size_t drop = 1;
    const auto span = [&](size_t c) {
      return keyframes_[first[c + 1]].records - keyframes_[first[c - 1]].records;
    };
    for (size_t c = 2; c + 1 < first.size(); ++c)
      if (span(c) < span(drop)) drop = c;
    const std::shared_ptr<const Volume> dropped = keyframes_[first[drop]].volume;
    const std::shared_ptr<const Volume> before = keyframes_[first[drop - 1]].volume;
    for (size_t k = first[drop]; k < first[drop + 1]; ++k) keyframes_[k].volume = before;
    held_bytes_ -= dropped->memoryBytes();
    --clouds_kept_;
    ++clouds_dropped_;
  }
}

size_t AttractReplay::keyframeBytes() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return held_bytes_;
}

size_t AttractReplay::peakKeyframeBytes() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return peak_bytes_;
}

size_t AttractReplay::cloudsKept() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return clouds_kept_;
}

size_t AttractReplay::cloudsDropped() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return clouds_dropped_;
}

std::vector<std::string> AttractReplay::problems() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return problems_;
}

}  // namespace cb
