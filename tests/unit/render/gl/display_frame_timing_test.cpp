#include "app/render/gl/display_frame_timing.h"

#include <gtest/gtest.h>

namespace cb {
namespace {

TEST(FrameTimingRing, EmptyHasNoLast) {
  FrameTimingRing ring;
  EXPECT_EQ(ring.size(), 0u);
  EXPECT_EQ(ring.last(), nullptr);
}

TEST(FrameTimingRing, KeepsTheNewestInOrderAfterWrapping) {
  FrameTimingRing ring;
  const uint64_t pushed = FrameTimingRing::kCapacity + 37;
  for (uint64_t i = 1; i <= pushed; ++i) {
    FrameTiming t;
    t.frame = i;
    t.vblank_sequence = uint32_t(1000 + i);
    ring.push(t);
  }
  ASSERT_EQ(ring.size(), FrameTimingRing::kCapacity);
  EXPECT_EQ(ring.total(), pushed);
  EXPECT_EQ(ring.at(0).frame, pushed - FrameTimingRing::kCapacity + 1);
  for (size_t i = 1; i < ring.size(); ++i) EXPECT_EQ(ring.at(i).frame, ring.at(i - 1).frame + 1);
  ASSERT_NE(ring.last(), nullptr);
  EXPECT_EQ(ring.last()->frame, pushed);
  EXPECT_EQ(ring.last()->vblank_sequence, 1000 + pushed);
}

}  // namespace
}  // namespace cb
