#include "app/shell/ui_overlay.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <list>

#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include "app/shell/keymap.h"

namespace cb {
namespace {

constexpr const char* kFontPath = "/usr/share/fonts/opentype/noto/NotoSansCJK-Regular.ttc";

struct MenuEntry {
  Command command;
  const char* label;  // English, then Chinese on the second line where the target is a mode
};

constexpr MenuEntry kModes[] = {{Command::kModeCamera, "Camera\n相机"},
                                {Command::kModeCanvas, "Canvas\n画布"},
                                {Command::kModePaint, "Paint\n绘画"},
                                {Command::kModeErase, "Erase\n擦除"},
                                {Command::kModeLight, "Light\n光照"}};

// The current mode's commands (thesis §3.4–3.5, Appendix A).
std::vector<MenuEntry> modeCommands(int mode) {
  switch (mode) {
    case 0:
      return {{Command::kResetCamera, "Reset view"},   {Command::kViewTop, "Top"},
              {Command::kViewFront, "Front"},          {Command::kViewLeft, "Left"},
              {Command::kViewPerspective, "3/4 view"}, {Command::kSpace, "Auto-rotate"}};
    case 1:
      return {{Command::kRaise, "Raise"},
              {Command::kLower, "Lower"},
              {Command::kSmaller, "Thinner"},
              {Command::kLarger, "Thicker"}};
    case 2:
      return {{Command::kNextBrush, "Next brush"},
              {Command::kBrushSmaller, "Brush −\n笔刷缩小"},
              {Command::kBrushLarger, "Brush +\n笔刷放大"},
              {Command::kNextMapping, "Mapping"},
              {Command::kToggleCircles, "Circles"},
              {Command::kGoodView, "Good view"}};
    case 3:
      return {{Command::kNextEraseTool, "Tool"},
              {Command::kSmaller, "Smaller"},
              {Command::kLarger, "Larger"},
              {Command::kSpace, "Cut"}};
    default:
      return {{Command::kSmaller, "Warmer"},
              {Command::kLarger, "Cooler"},
              {Command::kNextStyle, "Style"}};
  }
}

// Every character of the shipped labels, for the font atlas (Latin comes from the default
// range; the CJK characters are added one by one so the atlas stays small).
const char* shippedText() {
  return "相机画布绘画擦除光照菜单撤销重做笔刷缩小放大−";
}

}  // namespace

UiOverlay::UiOverlay() = default;

UiOverlay::~UiOverlay() {
  if (!context_) return;
  ImGui::SetCurrentContext(context_);
  if (ready_) ImGui_ImplOpenGL3_Shutdown();
  ImGui::DestroyContext(context_);
}

bool UiOverlay::init(std::string* error) {
  if (ready_) return true;
  context_ = ImGui::CreateContext();
  ImGui::SetCurrentContext(context_);
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // nothing written to disk
  io.LogFilename = nullptr;
  if (!std::filesystem::exists(kFontPath)) {
    *error = std::string("UI font ") + kFontPath + " is missing (install fonts-noto-cjk)";
    return false;
  }
  ImFontGlyphRangesBuilder ranges_builder;
  ranges_builder.AddRanges(io.Fonts->GetGlyphRangesDefault());
  ranges_builder.AddText(shippedText());
  ranges_builder.AddText(extra_glyphs_.c_str());
  // Must outlive the atlas build; one per overlay, since overlays may hold different glyphs.
  static std::list<ImVector<ImWchar>> all_ranges;
  ImVector<ImWchar>& ranges = all_ranges.emplace_back();
  ranges_builder.BuildRanges(&ranges);
  ImFontConfig config;
  config.OversampleH = 1;
  if (!io.Fonts->AddFontFromFileTTF(kFontPath, 26.0f, &config, ranges.Data)) {
    *error = std::string("UI font ") + kFontPath + " could not be loaded";
    return false;
  }
  ImGui::StyleColorsDark();
  ImGuiStyle& style = ImGui::GetStyle();
  style.WindowRounding = 10.0f;
  style.FrameRounding = 8.0f;
  style.WindowBorderSize = 0.0f;
  if (!ImGui_ImplOpenGL3_Init("#version 450 core")) {
    *error = "Dear ImGui's OpenGL 3 backend could not start";
    return false;
  }
  ready_ = true;
  return true;
}

void UiOverlay::pointer(float x, float y, bool down) {
  const bool last_down = pointer_queue_.empty() ? pointer_.down : pointer_queue_.back().down;
  if (!pointer_queue_.empty() && last_down == down)
    pointer_queue_.back() = {x, y, down};  // a move: only the latest position matters
  else
    pointer_queue_.push_back({x, y, down});
}

bool UiOverlay::targetRect(Command command, float rect[4]) const {
  for (const Target& t : targets_)
    if (t.command == command) {
      std::copy(t.rect, t.rect + 4, rect);
      return true;
    }
  return false;
}

std::vector<Command> UiOverlay::draw(int width, int height, double dt_s,
                                     const UiOverlayState& state) {
  std::vector<Command> tapped;
  if (!ready_) return tapped;
  ImGui::SetCurrentContext(context_);
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize = ImVec2(float(width), float(height));
  io.DeltaTime = float(std::clamp(dt_s, 1e-4, 0.5));
  if (!pointer_queue_.empty()) {
    pointer_ = pointer_queue_.front();
    pointer_queue_.erase(pointer_queue_.begin());
  }
  io.MousePos = ImVec2(pointer_.x, pointer_.y);
  io.MouseDown[0] = pointer_.down;
  // Text about 2.4% of the screen height (26 px at 1080 lines), never under 14 px.
  const float scale = std::max(14.0f / 26.0f, float(height) / 1080.0f);
  io.FontGlobalScale = scale;
  ImGui_ImplOpenGL3_NewFrame();
  ImGui::NewFrame();
  targets_.clear();
  const auto remember = [&](Command command) {
    const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
    targets_.push_back({command, {a.x, a.y, b.x, b.y}});
  };
  const ImGuiWindowFlags fixed = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                                 ImGuiWindowFlags_NoSavedSettings |
                                 ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav;

  // The status line along the top, with the menu button at its right end.
  const float bar_h = ImGui::GetFrameHeight() + 2.0f * ImGui::GetStyle().WindowPadding.y;
  ImGui::SetNextWindowPos(ImVec2(0.0f, 0.0f));
  ImGui::SetNextWindowSize(ImVec2(float(width), bar_h));
  ImGui::SetNextWindowBgAlpha(0.55f);
  ImGui::Begin("status", nullptr, fixed);
  const float button_w =
      ImGui::CalcTextSize("Close (M)").x + 4.0f * ImGui::GetStyle().FramePadding.x;
  ImGui::AlignTextToFramePadding();
  // The status text stops before the menu button (clipped on narrow screens).
  const ImVec2 text_pos = ImGui::GetCursorScreenPos();
  ImGui::PushClipRect(text_pos,
                      ImVec2(float(width) - button_w - 2.0f * ImGui::GetStyle().WindowPadding.x,
                             text_pos.y + bar_h),
                      true);
  ImGui::TextUnformatted(state.status.c_str());
  ImGui::PopClipRect();
  ImGui::SameLine(std::max(0.0f, float(width) - button_w - ImGui::GetStyle().WindowPadding.x));
  if (ImGui::Button(state.menu_open ? "Close (M)" : "Menu (M)", ImVec2(button_w, 0.0f)))
    tapped.push_back(Command::kMenu);
  const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
  menu_button_[0] = a.x, menu_button_[1] = a.y, menu_button_[2] = b.x, menu_button_[3] = b.y;
  ImGui::End();

  if (!state.notice.empty()) {
    // Sized from its text, so it shows on the frame it appears (an auto-sized ImGui window
    // stays hidden for its first frame).
    const ImVec2 padding = ImGui::GetStyle().WindowPadding;
    const ImVec2 text = ImGui::CalcTextSize(state.notice.c_str());
    ImGui::SetNextWindowPos(ImVec2(float(width) * 0.5f, bar_h + 8.0f), 0, ImVec2(0.5f, 0.0f));
    ImGui::SetNextWindowSize(ImVec2(text.x + 2.0f * padding.x, text.y + 2.0f * padding.y));
    ImGui::SetNextWindowBgAlpha(0.8f);
    ImGui::Begin("notice", nullptr, fixed);
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.85f, 0.4f, 1.0f));
    ImGui::TextUnformatted(state.notice.c_str());
    ImGui::PopStyleColor();
    ImGui::End();
  }

  if (state.menu_open) {
    // Big pen targets (thesis Fig. 3.7): five across take 70% of the screen's width (about
    // 75 mm each on a 24" screen), each a tenth of its height.
    const ImVec2 target(0.14f * float(width), 0.1f * float(height));
    ImGui::SetNextWindowPos(ImVec2(float(width) * 0.5f, float(height) * 0.45f), 0,
                            ImVec2(0.5f, 0.5f));
    ImGui::SetNextWindowBgAlpha(0.85f);
    ImGui::Begin("menu", nullptr, fixed | ImGuiWindowFlags_AlwaysAutoResize);
    const auto button = [&](Command command, const char* label, bool selected, bool enabled) {
      const std::string key = keyLabel(command);
      const std::string text =
          std::string(label) + (key.empty() ? "" : "  [" + key + "]") + "##" + commandName(command);
      if (selected) ImGui::PushStyleColor(ImGuiCol_Button, ImVec4(0.2f, 0.5f, 0.85f, 1.0f));
      if (!enabled) ImGui::BeginDisabled();
      if (ImGui::Button(text.c_str(), target)) tapped.push_back(command);
      if (!enabled) ImGui::EndDisabled();
      if (selected) ImGui::PopStyleColor();
      remember(command);
    };
    bool first = true;
    for (int i = 0; i < 5; ++i) {
      if (state.visitor && (i == 1 || i == 4)) continue;  // canvas and light: the operator's
      if (!first) ImGui::SameLine();
      first = false;
      button(kModes[i].command, kModes[i].label, state.mode == i, true);
    }
    ImGui::Separator();
    const std::vector<MenuEntry> commands = modeCommands(state.mode);
    for (size_t i = 0; i < commands.size(); ++i) {
      if (i % 5) ImGui::SameLine();
      button(commands[i].command, commands[i].label, false, true);
    }
    if (!state.visitor) {
      // The animations (issue 14): morph into a saved cloud, wind; apply or leave what shows.
      ImGui::Separator();
      button(Command::kMorph, "Morph", false, true);
      ImGui::SameLine();
      button(Command::kWind, "Wind", false, true);
      ImGui::SameLine();
      button(Command::kWindDirection, "Wind dir.", false, true);
      ImGui::SameLine();
      button(Command::kApplyAnimation, "Apply", false, state.animation);
      ImGui::SameLine();
      button(Command::kLeaveAnimation, "Leave", false, state.animation);
    }
    ImGui::Separator();
    button(Command::kUndo, "Undo\n撤销", false, state.can_undo);
    ImGui::SameLine();
    button(Command::kRedo, "Redo\n重做", false, state.can_redo);
    ImGui::SameLine();
    button(Command::kDeleteAll, state.visitor ? "Start again" : "Delete all", false, true);
    if (!state.visitor) {
      ImGui::SameLine();
      button(Command::kSave, "Save", false, true);
      ImGui::SameLine();
      button(Command::kOpen, "Open last", false, true);
      ImGui::SameLine();
      button(Command::kToggleStats, "Statistics", false, true);
    }
    ImGui::End();
  }
  over_ui_ = io.WantCaptureMouse;
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  return tapped;
}

}  // namespace cb

namespace cb {

void UiOverlay::drawLabels(int width, int height, const std::vector<UiLabel>& labels) {
  if (!ready_) return;
  ImGui::SetCurrentContext(context_);
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize = ImVec2(float(width), float(height));
  io.DeltaTime = 1.0f / 60.0f;
  io.FontGlobalScale = 1.0f;
  ImGui_ImplOpenGL3_NewFrame();
  ImGui::NewFrame();
  ImDrawList* draw = ImGui::GetForegroundDrawList();
  for (const UiLabel& label : labels) {
    const ImU32 colour = IM_COL32(label.rgba >> 24, (label.rgba >> 16) & 0xff,
                                  (label.rgba >> 8) & 0xff, label.rgba & 0xff);
    ImFont* font = ImGui::GetFont();
    const float wrap = label.centred ? 0.0f : label.wrap_width;
    const ImVec2 size = font->CalcTextSizeA(label.size_px, 1e9f, wrap, label.text.c_str());
    float x = label.x;
    if (label.centred) x -= 0.5f * size.x;
    if (label.background_rgba & 0xffu) {
      const uint32_t b = label.background_rgba;
      const float pad = 0.4f * label.size_px;
      draw->AddRectFilled(ImVec2(x - pad, label.y - 0.5f * pad),
                          ImVec2(x + size.x + pad, label.y + size.y + 0.5f * pad),
                          IM_COL32(b >> 24, (b >> 16) & 0xff, (b >> 8) & 0xff, b & 0xff),
                          0.3f * label.size_px);
    }
    draw->AddText(font, label.size_px, ImVec2(x, label.y), colour, label.text.c_str(), nullptr,
                  wrap);
  }
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

}  // namespace cb
