// The skeleton brush (thesis §5.2, Fig. 5.4): a spine of 4 joints (3 segments) hangs from the
// rod held by the pen. Joint 0 follows the pen; its height falls with pressure. The other joints
// move by position Verlet at a fixed internal time step (§5.2.1; the thesis prints
// 2·P_crt + (P_crt − P_prv), the correct update is x' = 2x − x_prev + a·dt²) with damping, then
// 10 iterations of distance constraints keep the segments rigid and the paper pushes them up.
// Bristles are cubic Bezier curves grown from the joints; the footprint records where bristles
// sink below the paper (§5.2.2), into a buffer never cleared during the stroke.
//
// Brush-local space: x, z = footprint pixels (x right, z down the footprint), y = height above
// the paper in pixels. The pen path is interpolated in time between samples, so the footprint
// does not depend on the report rate. Kept selectable although the thesis's users preferred the
// texture brushes: the bristle tip does not track the pen tip.
#pragma once

#include <array>
#include <vector>

#include <glm/glm.hpp>

#include "app/brush/brush.h"
#include "app/brush/dispersion.h"

namespace cb {

class SkeletonBrush : public Brush {
 public:
  explicit SkeletonBrush(const BrushConfig& config);
  BrushKind kind() const override { return BrushKind::kSkeleton; }
  FootprintRect beginStroke(uint32_t stroke_index, const StrokePoint& first,
                            Footprint* footprint) override;
  FootprintRect continueStroke(const StrokePoint& point, Footprint* footprint) override;
  FootprintRect endStroke(Footprint* footprint) override;
  void prepareStroke(uint32_t stroke_index) override;
  float reachPx() const override;

  const std::array<glm::vec3, 4>& joints() const { return joints_; }
  uint64_t stepCount() const { return steps_; }

 private:
  struct Bristle {
    glm::vec2 offset;  // direction × radius fraction in the xz plane
    float length;      // fraction of the last segment this bristle reaches
  };
  glm::vec3 rodPosition(const StrokePoint& p) const;
  glm::vec3 acceleration(const StrokePoint& p) const;
  void step(const StrokePoint& pen);
  // One step towards `pen`, then the bristles stamped along the spine's path since the last
  // stamp (when it moved).
  FootprintRect stepAndStamp(const StrokePoint& pen, Footprint* footprint);
  FootprintRect stampBristles(float pressure, Footprint* footprint);

  SkeletonParams params_;
  DispersionParams dispersion_params_;
  DispersionField field_;
  std::array<glm::vec3, 4> joints_{}, previous_{};
  std::array<glm::vec3, 4> stamped_joints_{};
  std::vector<Bristle> bristles_;
  StrokePoint last_input_{};
  int64_t sim_t_ns_ = 0;
  int64_t dt_ns_ = 1000000;
  float speed_px_s_ = 0.0f;
  uint64_t steps_ = 0;
};

}  // namespace cb
