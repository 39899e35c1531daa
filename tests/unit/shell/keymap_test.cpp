// One keymap: every command has a key that gives it back, modifiers matter only where they should,
// and scripted key lists parse or name what is wrong.
#include <gtest/gtest.h>

#include <xkbcommon/xkbcommon-keysyms.h>

#include "app/shell/keymap.h"

namespace cb {
namespace {

TEST(Keymap, EveryCommandHasAKeyThatGivesItBack) {
  for (int i = 0; i < int(Command::kCount); ++i) {
    const Command command = Command(i);
    const std::string label = keyLabel(command);
    ASSERT_FALSE(label.empty()) << commandName(command);
    std::string name = label;
    for (char& c : name) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (name == "pgup") name = "pageup";
    if (name == "pgdn") name = "pagedown";
    if (name == "del") name = "delete";
    if (name == "-") name = "minus";
    if (name == "+") name = "plus";
    if (name == "[") name = "bracketleft";
    if (name == "]") name = "bracketright";
    std::vector<DisplayEvent> keys;
    std::string error;
    ASSERT_TRUE(parseKeyList(name + ",", &keys, &error) || parseKeyList(name, &keys, &error))
        << name << ": " << error;
    ASSERT_FALSE(keys.empty());
    EXPECT_EQ(commandFor(keys.front()), command) << label;
    EXPECT_EQ(parseCommandName(commandName(command)), command);
  }
}

TEST(Keymap, ModifiersAndLayouts) {
  EXPECT_EQ(commandForKey('z', DisplayEvent::kCtrl), Command::kUndo);
  EXPECT_EQ(commandForKey('Z', DisplayEvent::kCtrl | DisplayEvent::kShift), Command::kRedo);
  EXPECT_EQ(commandForKey('y', DisplayEvent::kCtrl), Command::kRedo);
  EXPECT_EQ(commandForKey('z', 0), std::nullopt) << "z alone is nothing";
  EXPECT_EQ(commandForKey('B', DisplayEvent::kShift), Command::kNextBrush) << "Shift+b is still B";
  EXPECT_EQ(commandForKey('q', DisplayEvent::kCtrl), std::nullopt);
  EXPECT_EQ(commandForKey(XKB_KEY_KP_Add, 0), Command::kLarger);
  EXPECT_EQ(commandForKey(XKB_KEY_Left, 0), Command::kViewLeft);
  EXPECT_EQ(commandForKey(XKB_KEY_Left, DisplayEvent::kShift), Command::kPanLeft)
      << "Shift+arrows pan";
  EXPECT_EQ(commandForKey(XKB_KEY_Down, DisplayEvent::kShift), Command::kPanDown);
  EXPECT_EQ(commandForKey('P', DisplayEvent::kShift), Command::kPanDrag);
  DisplayEvent close;
  close.kind = DisplayEvent::Kind::Quit;
  EXPECT_EQ(commandFor(close), Command::kQuit);
}

TEST(Keymap, KeyListsParseOrNameTheBadKey) {
  std::vector<DisplayEvent> keys;
  std::string error;
  ASSERT_TRUE(parseKeyList("bm", &keys, &error)) << error;
  ASSERT_EQ(keys.size(), 2u);
  EXPECT_EQ(keys[1].keysym, uint32_t('m'));
  keys.clear();
  ASSERT_TRUE(parseKeyList("3,ctrl+z,space,Up", &keys, &error)) << error;
  ASSERT_EQ(keys.size(), 4u);
  EXPECT_EQ(keys[1].modifiers, uint32_t(DisplayEvent::kCtrl));
  EXPECT_EQ(keys[3].keysym, uint32_t(XKB_KEY_Up));
  keys.clear();
  ASSERT_TRUE(parseKeyList("delete", &keys, &error)) << error;
  ASSERT_EQ(keys.size(), 1u) << "a key's name is that key, not its letters";
  EXPECT_FALSE(parseKeyList("b,f00", &keys, &error));
  EXPECT_NE(error.find("f00"), std::string::npos) << error;
}

// The kiosk's operator combination may use a function key ([operator] keys in kiosk.toml).
TEST(Keymap, FunctionKeysParseAsOneKey) {
  std::vector<DisplayEvent> keys;
  std::string error;
  ASSERT_TRUE(parseKeyList("ctrl+alt+f12", &keys, &error)) << error;
  ASSERT_EQ(keys.size(), 1u);
  EXPECT_EQ(keys[0].keysym, uint32_t(XKB_KEY_F12));
  EXPECT_EQ(keys[0].modifiers, uint32_t(DisplayEvent::kCtrl | DisplayEvent::kAlt));
  keys.clear();
  ASSERT_TRUE(parseKeyList("f1", &keys, &error)) << error;
  ASSERT_EQ(keys.size(), 1u) << "f1 is F1, not f and 1";
  EXPECT_EQ(keys[0].keysym, uint32_t(XKB_KEY_F1));
  keys.clear();
  ASSERT_TRUE(parseKeyList("shift+f5,f10", &keys, &error)) << error;
  ASSERT_EQ(keys.size(), 2u);
  EXPECT_EQ(keys[0].keysym, uint32_t(XKB_KEY_F5));
  EXPECT_EQ(keys[1].keysym, uint32_t(XKB_KEY_F10));
  EXPECT_FALSE(parseKeyList("ctrl+f13", &keys, &error));
  EXPECT_NE(error.find("f1-f12"), std::string::npos) << error;
}

}  // namespace
}  // namespace cb
