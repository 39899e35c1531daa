// The KMS keyboard across SYN_DROPPED (drivers/keyboard/evdev_key_tracker.h), on event streams as
// the kernel's evdev writes them when a client's buffer overflows (drivers/input/evdev.c
// evdev_queue_syn_dropped: the buffer is emptied, SYN_DROPPED queued, then the live events): a
// Ctrl whose release was dropped is released by the resync, a key pressed and still held in
// the dropped part is pressed, and nothing is delivered twice. The real kernel's overflow is not
// exercised here (the host has no /dev/uinput).
#include "drivers/keyboard/evdev_key_tracker.h"

#include <gtest/gtest.h>

#include <set>

namespace cb {
namespace {

input_event ev(uint16_t type, uint16_t code, int32_t value) {
  input_event e{};
  e.type = type;
  e.code = code;
  e.value = value;
  return e;
}
input_event key(uint16_t code, int32_t value) {
  return ev(EV_KEY, code, value);
}
input_event report() {
  return ev(EV_SYN, SYN_REPORT, 0);
}

std::vector<uint8_t> keyBits(const std::set<int>& down) {
  std::vector<uint8_t> bits(KEY_CNT / 8 + 1, 0);
  for (int code : down) bits[size_t(code) / 8] |= uint8_t(1u << (code % 8));
  return bits;
}

using T = std::vector<std::pair<int, bool>>;
T pairs(const std::vector<KeyTransition>& keys) {
  T t;
  for (const KeyTransition& k : keys) t.emplace_back(k.code, k.down);
  return t;
}

TEST(EvdevKeyTracker, PressesAndReleasesPassRepeatsDoNot) {
  EvdevKeyTracker tracker;
  std::vector<KeyTransition> out;
  for (const input_event& e :
       {key(KEY_LEFTCTRL, 1), report(), key(KEY_Z, 1), report(), key(KEY_Z, 2), report(),
        key(KEY_Z, 0), key(KEY_LEFTCTRL, 0), report()})
    tracker.feed(e, &out);
  EXPECT_EQ(pairs(out),
            (T{{KEY_LEFTCTRL, true}, {KEY_Z, true}, {KEY_Z, false}, {KEY_LEFTCTRL, false}}));
  EXPECT_FALSE(tracker.needsResync());
}

TEST(EvdevKeyTracker, SynDroppedDiscardsToTheNextReportThenTheKeyStateIsReadAgain) {
  EvdevKeyTracker tracker;
  std::vector<KeyTransition> out;
  // Ctrl held; during a long frame the visitor released Ctrl and pressed (and holds) 3; the
  // buffer overflowed: the kernel kept SYN_DROPPED and what came after it.
  for (const input_event& e :
       {key(KEY_LEFTCTRL, 1), report(), ev(EV_SYN, SYN_DROPPED, 0), key(KEY_3, 1), report(),
        key(KEY_4, 1), report(), key(KEY_4, 0), report()})
    tracker.feed(e, &out);
  EXPECT_EQ(pairs(out), (T{{KEY_LEFTCTRL, true}, {KEY_4, true}, {KEY_4, false}}))
      << "the part before the next SYN_REPORT is incomplete and skipped";
  ASSERT_TRUE(tracker.needsResync());
  out.clear();
  const std::vector<uint8_t> now = keyBits({KEY_3});
  tracker.resync(now.data(), now.size(), &out);
  EXPECT_EQ(pairs(out), (T{{KEY_LEFTCTRL, false}, {KEY_3, true}}))
      << "Ctrl released (not stuck), 3 held: released keys first";
  EXPECT_FALSE(tracker.needsResync());
  EXPECT_FALSE(tracker.isDown(KEY_LEFTCTRL));
  EXPECT_TRUE(tracker.isDown(KEY_3));
  // The 3's own release arrives later; a press the resync already gave is not given again.
  out.clear();
  for (const input_event& e : {key(KEY_3, 1), report(), key(KEY_3, 0), report()})
    tracker.feed(e, &out);
  EXPECT_EQ(pairs(out), (T{{KEY_3, false}}));
}

TEST(EvdevKeyTracker, AResyncThatFindsNothingChangedDeliversNothing) {
  EvdevKeyTracker tracker;
  std::vector<KeyTransition> out;
  for (const input_event& e :
       {key(KEY_LEFTSHIFT, 1), report(), ev(EV_SYN, SYN_DROPPED, 0), report()})
    tracker.feed(e, &out);
  out.clear();
  const std::vector<uint8_t> now = keyBits({KEY_LEFTSHIFT});
  tracker.resync(now.data(), now.size(), &out);
  EXPECT_TRUE(out.empty());
  EXPECT_TRUE(tracker.isDown(KEY_LEFTSHIFT));
}

}  // namespace
}  // namespace cb
