// Typed UI changes: one formatter and parser, exact round trips, named errors.
#include <gtest/gtest.h>

#include "app/session/ui_change.h"

namespace cb {
namespace {

TEST(UiChange, EveryKindRoundTripsBitForBit) {
  Camera camera = Camera::reference().orbited(33.3f);
  camera.fov_y_deg = 37.25f;
  const std::vector<UiChange> changes = {
      ui::SetMode{Mode::kErase},
      ui::SetCamera{camera},
      ui::SetCamera{camera, CameraMove::kPan},
      ui::SetCamera{camera, CameraMove::kOrbit},
      ui::SetBrush{BrushKind::kSkeleton},
      ui::SetMapping{MappingMethod::kRayMarching},
      ui::SetCanvas{0.1234567f, 0.4f},
      ui::SetLight{glm::normalize(glm::vec3(0.3f, 0.9f, -0.1f)), glm::vec3(1.0f, 0.8f, 0.6f)},
      ui::SetEraseTool{EraseTool::kVacuum},
      ui::SetEraseDiameter{EraseTool::kRubOut, 0.0731f},
      ui::VacuumCut{glm::vec3(-0.25f, 0.5f, 1.0f / 3.0f), 0.15f},
      ui::Undo{},
      ui::Redo{},
      ui::DeleteAll{},
      ui::PenCapture{true},
      ui::ShowMenu{true},
      ui::ShowMenu{false},
      ui::SetStyle{"ink"},
      ui::SetBrushSize{2.44140625f},
      ui::SetBrushSize{0.8f * 3.0f}};
  for (const UiChange& change : changes) {
    const UiRecordText text = formatUiChange(change);
    UiChange parsed;
    std::string error;
    ASSERT_TRUE(parseUiChange(text.type, text.text, &parsed, &error)) << text.text << ": " << error;
    EXPECT_EQ(parsed.index(), change.index()) << text.text;
    EXPECT_EQ(formatUiChange(parsed).text, text.text);
  }
  // Floats survive exactly (9 significant digits).
  UiChange parsed;
  std::string error;
  const UiRecordText text = formatUiChange(ui::SetCamera{camera});
  ASSERT_TRUE(parseUiChange(text.type, text.text, &parsed, &error));
  EXPECT_EQ(std::get<ui::SetCamera>(parsed).camera.eye, camera.eye);
  EXPECT_EQ(std::get<ui::SetCamera>(parsed).camera.fov_y_deg, camera.fov_y_deg);
  EXPECT_EQ(formatUiChange(ui::SetMode{Mode::kLight}).type, JournalRecordType::kMode);
  const UiRecordText size = formatUiChange(ui::SetBrushSize{0.8f * 3.0f});
  ASSERT_TRUE(parseUiChange(size.type, size.text, &parsed, &error)) << error;
  EXPECT_EQ(std::get<ui::SetBrushSize>(parsed).size, 0.8f * 3.0f) << size.text;
}

TEST(UiChange, CameraMovesAreJournalledAndOldCameraRecordsReadAsSet) {
  UiChange parsed;
  std::string error;
  const Camera camera = Camera::reference();
  const UiRecordText pan = formatUiChange(ui::SetCamera{camera, CameraMove::kPan});
  EXPECT_NE(pan.text.find(",pan"), std::string::npos) << pan.text;
  ASSERT_TRUE(parseUiChange(pan.type, pan.text, &parsed, &error)) << error;
  EXPECT_EQ(std::get<ui::SetCamera>(parsed).move, CameraMove::kPan);
  EXPECT_EQ(std::get<ui::SetCamera>(parsed).camera.target, camera.target);
  // A record written before moves existed: seven numbers, read as a plain set.
  ASSERT_TRUE(parseUiChange(JournalRecordType::kUi, "camera=2.2,1.6,2.2,0,0,0,45", &parsed, &error))
      << error;
  EXPECT_EQ(std::get<ui::SetCamera>(parsed).move, CameraMove::kSet);
  EXPECT_EQ(formatUiChange(parsed).text, "camera=2.20000005,1.60000002,2.20000005,0,0,0,45");
  EXPECT_FALSE(
      parseUiChange(JournalRecordType::kUi, "camera=2,1,2,0,0,0,45,spin", &parsed, &error));
  EXPECT_NE(error.find("spin"), std::string::npos) << error;
}

TEST(UiChange, OldOrbitRecordsStillParse) {
  UiChange parsed;
  std::string error;
  ASSERT_TRUE(parseUiChange(JournalRecordType::kUi, "camera_orbit=20", &parsed, &error)) << error;
  EXPECT_EQ(std::get<ui::SetCamera>(parsed).camera.eye, Camera::reference().orbited(20.0f).eye);
}

TEST(UiChange, BadValuesAreNamed) {
  UiChange parsed;
  std::string error;
  const struct {
    JournalRecordType type;
    const char* text;
    const char* names;
  } bad[] = {{JournalRecordType::kMode, "sculpt", "sculpt"},
             {JournalRecordType::kUi, "canvas=0.1", "canvas"},
             {JournalRecordType::kUi, "canvas=0.1,-2", "thickness"},
             {JournalRecordType::kUi, "light=0,0,0,1,1,1", "direction"},
             {JournalRecordType::kUi, "camera=1,2,3,4,5,6,nan", "camera"},
             {JournalRecordType::kUi, "vacuum_cut=0,0,0,0", "radius"},
             {JournalRecordType::kUi, "erase_tool=spray", "spray"},
             {JournalRecordType::kUi, "zoom=2", "zoom"},
             {JournalRecordType::kUi, "brush_size=9", "brush_size"},
             {JournalRecordType::kUi, "brush_size=0.1", "brush_size"},
             {JournalRecordType::kUi, "nonsense", "nonsense"}};
  for (const auto& b : bad) {
    EXPECT_FALSE(parseUiChange(b.type, b.text, &parsed, &error)) << b.text;
    EXPECT_NE(error.find(b.names), std::string::npos) << b.text << " -> " << error;
  }
}

}  // namespace
}  // namespace cb
