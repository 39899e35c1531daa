#include "app/brush/brush.h"

#include "app/brush/brush_2d.h"
#include "app/brush/brush_3d.h"
#include "app/brush/skeleton_brush.h"

namespace cb {

std::unique_ptr<Brush> makeBrush(BrushKind kind, const BrushConfig& config) {
  switch (kind) {
    case BrushKind::k2D:
      return std::make_unique<Brush2D>(config);
    case BrushKind::k3D:
      return std::make_unique<Brush3D>(config);
    case BrushKind::kSkeleton:
      return std::make_unique<SkeletonBrush>(config);
  }
  return nullptr;
}

}  // namespace cb
