// The KMS keyboard's key codes become the keymap's commands: through an XKB keymap compiled by
// libxkbcommon from xkb-data (as on an installed kiosk), and through the built-in US table used
// where no keymap compiles (a minimal initramfs). Both give the mode keys, Ctrl+Z and Delete.
#include <gtest/gtest.h>

#include <linux/input-event-codes.h>
#include <xkbcommon/xkbcommon.h>

#include "app/render/gl/display_kms_keyboard.h"
#include "app/shell/keymap.h"

namespace cb {
namespace {

TEST(KmsKeyboard, BuiltInTableGivesTheModeKeysUndoAndDelete) {
  EXPECT_EQ(commandForKey(EvdevKeyboards::fallbackKeysym(KEY_1, false), 0), Command::kModeCamera);
  EXPECT_EQ(commandForKey(EvdevKeyboards::fallbackKeysym(KEY_5, false), 0), Command::kModeLight);
  EXPECT_EQ(commandForKey(EvdevKeyboards::fallbackKeysym(KEY_Z, false), DisplayEvent::kCtrl),
            Command::kUndo);
  EXPECT_EQ(commandForKey(EvdevKeyboards::fallbackKeysym(KEY_DELETE, false), 0),
            Command::kDeleteAll);
  EXPECT_EQ(EvdevKeyboards::fallbackKeysym(KEY_M, true), uint32_t('M'));
  EXPECT_EQ(commandForKey(EvdevKeyboards::fallbackKeysym(KEY_UP, false), 0), Command::kViewTop);
}

// A German layout moves Z: the key labelled Z (evdev KEY_Y) still undoes with Ctrl.
TEST(KmsKeyboard, XkbKeymapFollowsTheLayout) {
  xkb_context* context = xkb_context_new(XKB_CONTEXT_NO_FLAGS);
  ASSERT_TRUE(context);
  const xkb_rule_names names{nullptr, nullptr, "de", nullptr, nullptr};
  xkb_keymap* keymap = xkb_keymap_new_from_names(context, &names, XKB_KEYMAP_COMPILE_NO_FLAGS);
  ASSERT_TRUE(keymap) << "no XKB keymap compiles: is xkb-data installed (config/setup.sh)?";
  xkb_state* state = xkb_state_new(keymap);
  const uint32_t z = xkb_state_key_get_one_sym(state, KEY_Y + 8);
  EXPECT_EQ(commandForKey(z, DisplayEvent::kCtrl), Command::kUndo);
  EXPECT_EQ(commandForKey(xkb_state_key_get_one_sym(state, KEY_3 + 8), 0), Command::kModePaint);
  xkb_state_unref(state);
  xkb_keymap_unref(keymap);
  xkb_context_unref(context);
}

}  // namespace
}  // namespace cb
