// The attract loop's replay, worked out once on a thread of its own: the bundled journal is
// replayed into a session of the worker's (brush, mapping, every stroke's cloud) and what the
// attract loop shows after each record that changed it — the cloud, camera, sun and style — is
// kept as a keyframe at that record's journal time. The attract screen (attract_screen.h) then
// only picks the keyframe due by the clock: its frame loop never maps a stroke. Mapping in the
// loop cost a stroke's whole mapping per frame (under an emulated CPU 6–19 s per frame, as the
// replay fell behind and tried to catch up), and a visitor plugging in a pen or picking it up
// waited that long for the hand-over.
//
// The journal is replayed once per kiosk run; every attract loop after an idle reset shows the
// same keyframes. Keyframes hold copies of the cloud only where it changed (a stroke's mapping),
// and those copies together stay within a budget of bytes: a copy of the whole cloud at every
// stroke grows with the square of a long journal's length (each copy is as large as everything
// painted so far). Over the budget, the cloud of the stroke whose neighbours lie closest
// together (in records) is dropped: its keyframes show the cloud before it, so that stroke
// appears with the next one. The empty sky and the newest cloud always stay, so the copies hold
// at most the budget plus the newest cloud, whatever the journal's length. Measured with a
// generated 96-stroke journal at the kiosk's grid (256): a copy per stroke held 509 MiB; with
// the default budget at most 134 MiB (24 of its 97 clouds kept).
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "app/brush/brush_config.h"
#include "app/mapping/mapping_config.h"
#include "app/scene/camera.h"
#include "app/scene/light.h"
#include "app/session/paint_session.h"
#include "app/volume/volume.h"
#include "drivers/core/journal.h"

namespace cb {

struct AttractKeyframe {
  int64_t t_ns = 0;    // journal time since the first record
  size_t records = 0;  // records applied to reach it (the first keyframe: 0, an empty sky)
  std::shared_ptr<const Volume> volume;
  Camera camera;
  Light light;
  std::string style;
};

class AttractReplay {
 public:
  // Starts the worker. `journal` is replayed in `settings` (its Session record is skipped: the
  // settings were made from it), starting with `light`.
  // `keyframe_budget_bytes`: the clouds the keyframes hold (Volume::memoryBytes of each
  // distinct copy) are thinned to stay within it.
  AttractReplay(std::vector<JournalRecord> journal, PaintSessionSettings settings,
                BrushConfig brush, MappingConfig mapping, Light light,
                size_t keyframe_budget_bytes = kDefaultKeyframeBudgetBytes);
  static constexpr size_t kDefaultKeyframeBudgetBytes = size_t(128) << 20;
  ~AttractReplay();  // stops the worker between two records
  AttractReplay(const AttractReplay&) = delete;
  AttractReplay& operator=(const AttractReplay&) = delete;

  size_t recordCount() const { return journal_.size(); }
  // Journal time of record i since the first record.
  int64_t recordTime(size_t i) const { return journal_[i].t_ns - journal_.front().t_ns; }
  // Records replayed so far (every keyframe up to there is available).
  size_t recordsReplayed() const { return replayed_.load(); }
  bool finished() const { return replayed_.load() == journal_.size(); }
  void waitUntilFinished() const;
  // The last keyframe reached with at most `records` records applied (the first always exists).
  AttractKeyframe keyframeAt(size_t records) const;
  // Records that did not apply (at most 20), as "attract journal record I: why".
  std::vector<std::string> problems() const;
  // Bytes of the distinct clouds the keyframes hold now, and the most they held at any time
  // (counted as each new cloud arrives, before the thinning it may cause).
  size_t keyframeBytes() const;
  size_t peakKeyframeBytes() const;
  // Clouds kept (distinct copies, the empty sky included) and clouds dropped by the thinning.
  size_t cloudsKept() const;
  size_t cloudsDropped() const;

 private:
  void run(PaintSessionSettings settings, BrushConfig brush, MappingConfig mapping, Light light);
  // Drops clouds (not the first or the newest) until the keyframes hold at most the budget.
  // Called with mutex_ held.
  void thinClouds();

  const std::vector<JournalRecord> journal_;
  const size_t budget_bytes_;
  mutable std::mutex mutex_;
  size_t held_bytes_ = 0, peak_bytes_ = 0;       // guarded by mutex_
  size_t clouds_kept_ = 1, clouds_dropped_ = 0;  // guarded by mutex_
  mutable std::condition_variable progressed_;
  std::vector<AttractKeyframe> keyframes_;  // guarded by mutex_, by ascending records
  std::vector<std::string> problems_;       // guarded by mutex_
  std::atomic<size_t> replayed_{0};
  std::atomic<bool> stop_{false};
  std::thread worker_;
};

}  // namespace cb
