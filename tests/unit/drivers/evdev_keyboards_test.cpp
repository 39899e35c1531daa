// The KMS keyboard's key codes become the keymap's commands: through an XKB keymap compiled by
// libxkbcommon from xkb-data (as on an installed kiosk), and through the built-in US table used
// where no keymap compiles (a minimal initramfs). Both give the mode keys, Ctrl+Z and Delete.
#include <gtest/gtest.h>

#include <linux/input-event-codes.h>
#include <xkbcommon/xkbcommon.h>

#include "app/shell/keymap.h"
#include "drivers/keyboard/evdev_keyboards.h"

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

// F1-F12 (an operator combination may use them), Page Up/Down, Home, End and Insert: the
// keysyms an XKB keymap gives for the same key codes (compared where xkb-data is installed).
TEST(KmsKeyboard, BuiltInTableHasTheFunctionAndNavigationKeys) {
  const int f_codes[12] = {KEY_F1, KEY_F2, KEY_F3, KEY_F4,  KEY_F5,  KEY_F6,
                           KEY_F7, KEY_F8, KEY_F9, KEY_F10, KEY_F11, KEY_F12};
  for (int i = 0; i < 12; ++i) {
    EXPECT_EQ(EvdevKeyboards::fallbackKeysym(f_codes[i], false), uint32_t(XKB_KEY_F1 + i))
        << "F" << i + 1;
    EXPECT_EQ(EvdevKeyboards::fallbackKeysym(f_codes[i], true), uint32_t(XKB_KEY_F1 + i));
  }
  std::vector<DisplayEvent> keys;
  std::string error;
  ASSERT_TRUE(parseKeyList("ctrl+alt+f12", &keys, &error)) << error;
  EXPECT_EQ(EvdevKeyboards::fallbackKeysym(KEY_F12, false), keys[0].keysym);
  xkb_context* context = xkb_context_new(XKB_CONTEXT_NO_FLAGS);
  ASSERT_TRUE(context);
  const xkb_rule_names names{nullptr, nullptr, "us", nullptr, nullptr};
  xkb_keymap* keymap = xkb_keymap_new_from_names(context, &names, XKB_KEYMAP_COMPILE_NO_FLAGS);
  ASSERT_TRUE(keymap) << "no XKB keymap compiles: is xkb-data installed (config/setup.sh)?";
  xkb_state* state = xkb_state_new(keymap);
  for (int code : {KEY_F1, KEY_F5, KEY_F10, KEY_F11, KEY_F12, KEY_PAGEUP, KEY_PAGEDOWN, KEY_HOME,
                   KEY_END, KEY_INSERT, KEY_ESC, KEY_DELETE, KEY_UP, KEY_A, KEY_0})
    EXPECT_EQ(EvdevKeyboards::fallbackKeysym(code, false),
              xkb_state_key_get_one_sym(state, code + 8))
        << "key code " << code;
  xkb_state_unref(state);
  xkb_keymap_unref(keymap);
  xkb_context_unref(context);
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
