// How the painter draws a frame while the view moves (the orbit, a drag turning the view, a
// morph or the wind): at the reduced moving scale (blurred, PaintLoopOptions::moving_scale), or
// at full resolution by temporal reprojection (app/render/temporal_reprojection.h: one pixel in
// 16 cast, the rest reprojected). Neither is always the faster on llvmpipe: reprojection pays a
// full-resolution pass (~25 ms at 1920×1080) and casts a quarter of the half-resolution frame's
// rays, so it wins where the rays are dear (a close, dense cloud: the painter's starting view)
// and loses where they are cheap (a far or thin one: the idle orbit).
#pragma once

#include <algorithm>
#include <array>

namespace cb {

enum class MovingFrames {
  kReduced,      // always the moving scale
  kReprojected,  // always full resolution by reprojection (where it applies)
  kFaster,       // reprojection while it keeps to the frame budget or is the faster, measured
};

// kFaster's choice, from each path's measured frame time (the median of its last kKept frames,
// so one slow frame — a PNG written, another process — does not turn it; each path's first frame
// ever is left out: it compiles its programs and makes its targets).
// Reprojection first, kept while within budget_ms; over it, one reduced frame is measured, and
// from then on the faster of the two is drawn, the other measured again for one frame every
// kReprobeFrames and at the first frame of each movement after a rest (the view may have moved
// to where it is the faster: a close, dense cloud against a far, thin one).
class MovingPathChooser {
 public:
  static constexpr int kReprobeFrames = 90;  // 3 s at 30 fps, 6 s at 15 fps
  static constexpr int kKept = 5;

  MovingPathChooser(MovingFrames policy, double budget_ms)
      : policy_(policy), budget_ms_(budget_ms) {}

  // Whether the next moving frame is to be reprojected.
  bool reprojectNext() const {
    if (policy_ != MovingFrames::kFaster) return policy_ == MovingFrames::kReprojected;
    if (ms(1) < 0.0 || ms(1) <= budget_ms_) return true;
    if (ms(0) < 0.0) return false;
    const bool faster = preferred();
    return frames_since_probe_ >= kReprobeFrames ? !faster : faster;
  }
  // A moving frame drawn `reprojected` (or not) took frame_ms, from its start to its present.
  void measured(bool reprojected, double frame_ms) {
    const int path = reprojected ? 1 : 0;
    if (!warm_[path]) {
      warm_[path] = true;
      return;
    }
    // A probe (the path not preferred) replaces its old frames, which may be far out of date.
    const bool probe = ms(0) >= 0.0 && ms(1) >= 0.0 && reprojected != preferred();
    Kept& kept = kept_[path];
    if (probe) kept = Kept{};
    kept.ms[kept.next] = frame_ms;  // over the oldest once full
    kept.next = (kept.next + 1) % kKept;
    kept.count = std::min(kept.count + 1, kKept);
    frames_since_probe_ = probe ? 0 : frames_since_probe_ + 1;
  }
  // A frame with nothing moving: the next movement starts with the other path's probe.
  void rested() { frames_since_probe_ = kReprobeFrames; }
  double reprojectedMs() const { return ms(1); }  // < 0: not measured yet
  double reducedMs() const { return ms(0); }

 private:
  // The median of path's kept frames (the upper one of an even count); < 0: none.
  double ms(int path) const {
    Kept k = kept_[path];
    if (k.count == 0) return -1.0;
    std::nth_element(k.ms.begin(), k.ms.begin() + k.count / 2, k.ms.begin() + k.count);
    return k.ms[size_t(k.count / 2)];
  }
  bool preferred() const { return ms(1) <= budget_ms_ || ms(1) <= ms(0); }

  MovingFrames policy_;
  double budget_ms_;
  struct Kept {
    std::array<double, kKept> ms{};  // the last `count` frames' times
    int count = 0, next = 0;         // next: where the next one goes (over the oldest)
  };
  Kept kept_[2];  // reduced, reprojected
  bool warm_[2] = {false, false};
  int frames_since_probe_ = 0;
};

}  // namespace cb
