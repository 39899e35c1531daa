#include "app/shell/ui_overlay.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <list>

#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>
#include <imgui_internal.h>

#include "app/shell/keymap.h"
#include "app/shell/painter/painter_messages.h"

namespace cb {
namespace {

std::function<void(const std::string&)>& textObserver() {
  static std::function<void(const std::string&)> observer;
  return observer;
}

// Tells the observer (if any) about a text drawn; a target's "##id" suffix is not drawn.
void observe(const std::string& text) {
  if (textObserver()) textObserver()(text.substr(0, text.find("##")));
}

constexpr const char* kFontPath = "/usr/share/fonts/opentype/noto/NotoSansCJK-Regular.ttc";

// The current mode's commands (thesis §3.4–3.5, Appendix A); labels from command_table.h.
std::vector<Command> modeCommands(int mode) {
  switch (mode) {
    case 0:
      return {Command::kResetCamera,     Command::kViewTop, Command::kViewFront, Command::kViewLeft,
              Command::kViewPerspective, Command::kSpace,   Command::kSmaller,   Command::kLarger};
    case 1:
      return {Command::kRaise, Command::kLower, Command::kSmaller, Command::kLarger};
    case 2:
      return {Command::kNextBrush,   Command::kBrushSmaller,  Command::kBrushLarger,
              Command::kNextMapping, Command::kToggleCircles, Command::kGoodView};
    case 3:
      return {Command::kNextEraseTool, Command::kSmaller, Command::kLarger, Command::kSpace};
    default:
      return {Command::kSmaller, Command::kLarger, Command::kNextStyle};
  }
}

// The menu's words for `command` in `mode`, English over Chinese.
std::string menuLabel(Command command, int mode) {
  return commandLabelIn(command, Mode(mode)).twoLines();
}

// Every character of the shipped labels, for the font atlas (Latin comes from the default
// range; the CJK characters are added one by one so the atlas stays small).
std::string shippedText() {
  return commandTableText() + painterMessagesText() + "重新开始关闭";
}

// Text about 2.4% of the screen height (26 px at 1080 lines), never under 14 px.
float fontScale(int height) {
  return std::max(14.0f / 26.0f, float(height) / 1080.0f);
}

// The box of `lines` at `size_px` centred at (x, y_top): widest line and padding (x0, y0, x1, y1).
void textBoxRect(ImFont* font, float x, float y, const std::vector<std::string>& lines,
                 float size_px, float rect[4]) {
  float w = 0.0f;
  for (const std::string& l : lines)
    w = std::max(w, font->CalcTextSizeA(size_px, 1e9f, 0.0f, l.c_str()).x);
  const float line_h = size_px * 1.25f, pad = 0.6f * size_px;
  rect[0] = x - 0.5f * w - pad, rect[1] = y - pad, rect[2] = x + 0.5f * w + pad;
  rect[3] = y + line_h * float(lines.size()) + pad;
}

// A box of lines centred at (x, y_top), drawn on the foreground (no window, no input); its
// rectangle goes to *rect when given.
void drawTextBox(ImDrawList* draw, float x, float y, const std::vector<std::string>& lines,
                 float size_px, ImU32 colour, ImU32 background, float* rect = nullptr) {
  ImFont* font = ImGui::GetFont();
  float box[4];
  textBoxRect(font, x, y, lines, size_px, box);
  draw->AddRectFilled(ImVec2(box[0], box[1]), ImVec2(box[2], box[3]), background, 0.4f * size_px);
  if (rect) std::copy(box, box + 4, rect);
  const float line_h = size_px * 1.25f;
  for (size_t i = 0; i < lines.size(); ++i) {
    observe(lines[i]);
    const float lw = font->CalcTextSizeA(size_px, 1e9f, 0.0f, lines[i].c_str()).x;
    draw->AddText(font, size_px, ImVec2(x - 0.5f * lw, y + line_h * float(i)), colour,
                  lines[i].c_str());
  }
}

// The toast's and the hint's centre: the middle of the message area.
float messageCentre(int width, const UiOverlayState& state) {
  return 0.5f * (state.message_width > 0.0f ? state.message_width : float(width));
}

// The first screen's hint: low in the middle, where the eye goes after the cloud, above what
// the host draws along the bottom. Its lines' top and size at the UI's font size `font_px`.
struct HintPlace {
  float y, size_px;
};
HintPlace hintPlace(int height, const UiOverlayState& state, float font_px) {
  const float size = 1.2f * font_px;
  return {float(height) - state.message_bottom - (1.25f * float(state.hint.size()) + 2.5f) * size,
          size};
}

}  // namespace

UiOverlay::UiOverlay() = default;

UiOverlay::~UiOverlay() {
  if (!context_) return;
  ImGui::SetCurrentContext(context_);
  if (ready_) ImGui_ImplOpenGL3_Shutdown();
  ImGui::DestroyContext(context_);
}

bool UiOverlay::initFont(std::string* error) {
  if (context_) return true;
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
  ranges_builder.AddText(shippedText().c_str());
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
  // Built now (not at the first frame) so labelRect measures before anything is drawn.
  io.Fonts->Build();
  return true;
}

bool UiOverlay::init(std::string* error) {
  if (ready_) return true;
  if (!initFont(error)) return false;
  ImGui::SetCurrentContext(context_);
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

void UiOverlay::setTextObserver(std::function<void(const std::string&)> observer) {
  textObserver() = std::move(observer);
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
  const float scale = fontScale(height);
  io.FontGlobalScale = scale;
  ImGui_ImplOpenGL3_NewFrame();
  ImGui::NewFrame();
  targets_.clear();
  const ImGuiWindowFlags fixed = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                                 ImGuiWindowFlags_NoSavedSettings |
                                 ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav;

  // The status line along the top, with the menu button at its right end.
  const float bar_h = ImGui::GetFrameHeight() + 2.0f * ImGui::GetStyle().WindowPadding.y;
  ImGui::SetNextWindowPos(ImVec2(0.0f, 0.0f));
  ImGui::SetNextWindowSize(ImVec2(float(width), bar_h));
  ImGui::SetNextWindowBgAlpha(0.55f);
  ImGui::Begin("status", nullptr, fixed);
  const std::string menu_label = state.visitor_words ? (state.menu_open ? state.visitor_words->close
                                                                        : state.visitor_words->menu)
                                                     : (state.menu_open ? "Close (M)" : "Menu (M)");
  const float button_w =
      std::max(ImGui::CalcTextSize("Close (M)").x, ImGui::CalcTextSize(menu_label.c_str()).x) +
      4.0f * ImGui::GetStyle().FramePadding.x;
  ImGui::AlignTextToFramePadding();
  // The status text stops before the menu button (clipped on narrow screens).
  const ImVec2 text_pos = ImGui::GetCursorScreenPos();
  ImGui::PushClipRect(text_pos,
                      ImVec2(float(width) - button_w - 2.0f * ImGui::GetStyle().WindowPadding.x,
                             text_pos.y + bar_h),
                      true);
  observe(state.status);
  ImGui::TextUnformatted(state.status.c_str());
  status_fits_ = ImGui::GetItemRectMax().x <=
                 float(width) - button_w - 2.0f * ImGui::GetStyle().WindowPadding.x;
  ImGui::PopClipRect();
  ImGui::SameLine(std::max(0.0f, float(width) - button_w - ImGui::GetStyle().WindowPadding.x));
  observe(menu_label);
  if (ImGui::Button(menu_label.c_str(), ImVec2(button_w, 0.0f))) tapped.push_back(Command::kMenu);
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
    observe(state.notice);
    ImGui::TextUnformatted(state.notice.c_str());
    ImGui::PopStyleColor();
    ImGui::End();
  }

  std::fill(hint_rect_, hint_rect_ + 4, 0.0f);
  if (state.help.empty()) drawMessages(width, height, bar_h, state);

  if (state.menu_open) drawMenu(width, height, state, fixed, &tapped);
  over_ui_ = io.WantCaptureMouse;
  if (!state.help.empty()) drawHelp(width, height, state.help);
  if (state.visitor_words && !state.visitor_words->help.empty()) {
    // The visitor's help: the kiosk's lines in a box over the dimmed painting.
    ImDrawList* back = ImGui::GetForegroundDrawList();
    back->AddRectFilled(ImVec2(0.0f, bar_h), ImVec2(float(width), float(height)),
                        IM_COL32(0, 0, 0, 150));
    drawTextBox(back, 0.5f * float(width), 0.3f * float(height), state.visitor_words->help,
                1.1f * ImGui::GetFontSize(), IM_COL32(255, 255, 255, 255),
                IM_COL32(20, 40, 70, 230));
  }
  ImDrawList* draw = ImGui::GetForegroundDrawList();
  for (const UiLabel& label : state.labels) {
    observe(label.text);
    draw->AddText(ImGui::GetFont(), label.size_px * scale, ImVec2(label.x, label.y),
                  IM_COL32(label.rgba >> 24, (label.rgba >> 16) & 0xff, (label.rgba >> 8) & 0xff,
                           label.rgba & 0xff),
                  label.text.c_str());
  }
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  last_draw_ = true;
  return tapped;
}

bool UiOverlay::redraw(const glm::ivec4& box) {
  if (!ready_ || !last_draw_) return false;
  ImGui::SetCurrentContext(context_);
  ImDrawData* data = ImGui::GetDrawData();
  if (!data || !data->Valid) return false;
  if (data->FramebufferScale.x != 1.0f || data->FramebufferScale.y != 1.0f) return false;
  if (box.z <= box.x || box.w <= box.y) return true;
  const int fb_h = int(data->DisplaySize.y);
  const ImVec2 off = data->DisplayPos;
  // Each command's clip rectangle becomes the pixels the OpenGL backend scissored it to (its
  // own float-to-int rounding, imgui_impl_opengl3.cpp) within `box`, in whole pixels, so every
  // pixel is drawn as the first draw drew it, and none outside the box.
  std::vector<ImVec4> kept;
  for (int n = 0; n < data->CmdListsCount; ++n)
    for (ImDrawCmd& cmd : data->CmdLists[n]->CmdBuffer) {
      kept.push_back(cmd.ClipRect);
      const float x0 = cmd.ClipRect.x - off.x, y0 = cmd.ClipRect.y - off.y;
      const float x1 = cmd.ClipRect.z - off.x, y1 = cmd.ClipRect.w - off.y;
      const int sx = int(x0), sw = int(x1 - x0);
      const int gl_y = int(float(fb_h) - y1), sh = int(y1 - y0);
      const int top = fb_h - gl_y - sh, bottom = fb_h - gl_y;  // rows, y down
      const int cx0 = std::max(sx, box.x), cx1 = std::min(sx + sw, box.z);
      const int cy0 = std::max(top, box.y), cy1 = std::min(bottom, box.w);
      cmd.ClipRect = cx1 > cx0 && cy1 > cy0 ? ImVec4(float(cx0) + off.x, float(cy0) + off.y,
                                                     float(cx1) + off.x, float(cy1) + off.y)
                                            : ImVec4(0.0f, 0.0f, 0.0f, 0.0f);
    }
  ImGui_ImplOpenGL3_RenderDrawData(data);
  size_t i = 0;
  for (int n = 0; n < data->CmdListsCount; ++n)
    for (ImDrawCmd& cmd : data->CmdLists[n]->CmdBuffer) cmd.ClipRect = kept[i++];
  return true;
}

int UiOverlay::missingGlyphs(const std::string& utf8_text) const {
  if (!ready_) return -1;
  ImGui::SetCurrentContext(context_);
  ImFont* font = ImGui::GetIO().Fonts->Fonts[0];
  int missing = 0;
  const char* p = utf8_text.c_str();
  const char* end = p + utf8_text.size();
  while (p < end) {
    unsigned int c = 0;
    const int n = ImTextCharFromUtf8(&c, p, end);
    if (n <= 0) break;
    p += n;
    if (c > ' ' && !font->FindGlyphNoFallback(ImWchar(c))) ++missing;
  }
  return missing;
}

void UiOverlay::drawMenu(int width, int height, const UiOverlayState& state, int window_flags,
                         std::vector<Command>* tapped) {
  // Big pen targets (thesis Fig. 3.7): five across take 70% of the screen's width (about
  // 75 mm each on a 24" screen), each a tenth of its height.
  const ImVec2 target(0.14f * float(width), 0.1f * float(height));
  ImGui::SetNextWindowPos(ImVec2(float(width) * 0.5f, float(height) * 0.45f), 0,
                          ImVec2(0.5f, 0.5f));
  ImGui::SetNextWindowBgAlpha(0.85f);
  ImGui::Begin("menu", nullptr, window_flags | ImGuiWindowFlags_AlwaysAutoResize);
  const auto button = [&](Command command, const std::string& label, bool selected, bool enabled) {
    const std::string key = state.visitor_words ? "" : keyLabel(command);
    const std::string text =
        label + (key.empty() ? "" : "  [" + key + "]") + "##" + commandName(command);
    if (selected) ImGui::PushStyleColor(ImGuiCol_Button, ImVec4(0.2f, 0.5f, 0.85f, 1.0f));
    if (!enabled) ImGui::BeginDisabled();
    observe(text);
    if (ImGui::Button(text.c_str(), target)) tapped->push_back(command);
    if (!enabled) ImGui::EndDisabled();
    if (selected) ImGui::PopStyleColor();
    const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
    targets_.push_back({command, {a.x, a.y, b.x, b.y}});
  };
  if (state.visitor_words) {
    // The kiosk's visitor: its own words, rows as the kiosk lays them out.
    const std::vector<VisitorMenuRow>& rows = state.visitor_words->rows;
    for (size_t r = 0; r < rows.size(); ++r) {
      if (r > 0) ImGui::Separator();
      for (size_t i = 0; i < rows[r].size(); ++i) {
        const Command c = rows[r][i].first;
        if (i % 5) ImGui::SameLine();
        const int mode = int(c) - int(Command::kModeCamera);
        const bool enabled = c == Command::kUndo   ? state.can_undo
                             : c == Command::kRedo ? state.can_redo
                                                   : true;
        button(c, rows[r][i].second, mode >= 0 && mode < 5 && mode == state.mode, enabled);
      }
    }
    ImGui::End();
    return;
  }
  bool first = true;
  for (int i = 0; i < 5; ++i) {
    if (state.visitor && (i == 1 || i == 4)) continue;  // canvas and light: the operator's
    if (!first) ImGui::SameLine();
    first = false;
    const Command mode = Command(int(Command::kModeCamera) + i);
    button(mode, modeLabel(Mode(i)).twoLines(), state.mode == i, true);
  }
  ImGui::Separator();
  const std::vector<Command> commands = modeCommands(state.mode);
  for (size_t i = 0; i < commands.size(); ++i) {
    if (i % 5) ImGui::SameLine();
    button(commands[i], menuLabel(commands[i], state.mode), false, true);
  }
  if (!state.visitor) {
    // The animations: morph into a saved cloud, wind; apply or leave what shows.
    ImGui::Separator();
    const Command animations[] = {Command::kMorph, Command::kWind, Command::kWindDirection,
                                  Command::kApplyAnimation, Command::kLeaveAnimation};
    for (Command c : animations) {
      if (c != Command::kMorph) ImGui::SameLine();
      const bool needs_animation = c == Command::kApplyAnimation || c == Command::kLeaveAnimation;
      button(c, menuLabel(c, state.mode), false, !needs_animation || state.animation);
    }
  }
  ImGui::Separator();
  button(Command::kUndo, menuLabel(Command::kUndo, state.mode), false, state.can_undo);
  ImGui::SameLine();
  button(Command::kRedo, menuLabel(Command::kRedo, state.mode), false, state.can_redo);
  ImGui::SameLine();
  button(Command::kDeleteAll,
         state.visitor ? std::string("Start again\n重新开始")
                       : menuLabel(Command::kDeleteAll, state.mode),
         false, true);
  ImGui::SameLine();
  button(Command::kHelp, menuLabel(Command::kHelp, state.mode), false, true);
  if (!state.visitor) {
    const Command files[] = {Command::kSave, Command::kOpen, Command::kToggleStats};
    for (Command c : files) {
      if (c != Command::kSave) ImGui::SameLine();
      button(c, menuLabel(c, state.mode), false, true);
    }
  }
  ImGui::End();
}

void UiOverlay::drawMessages(int width, int height, float bar_h, const UiOverlayState& state) {
  ImDrawList* draw = ImGui::GetForegroundDrawList();
  const float size = ImGui::GetFontSize();
  // The answer to the last action, under the status line (and under a notice); below the
  // open menu, which fills the middle, so neither hides the other.
  const float toast_y = state.menu_open ? float(height) - 2.2f * size
                                        : bar_h + (state.notice.empty() ? 1.0f : 3.2f) * size;
  const float centre = messageCentre(width, state);
  std::fill(toast_rect_, toast_rect_ + 4, 0.0f);
  if (!state.toast.empty())
    drawTextBox(draw, centre, toast_y, {state.toast}, size, IM_COL32(255, 255, 255, 255),
                IM_COL32(20, 40, 70, 215), toast_rect_);
  if (!state.hint.empty() && !state.menu_open) {
    const HintPlace hint = hintPlace(height, state, size);
    drawTextBox(draw, centre, hint.y, state.hint, hint.size_px, IM_COL32(255, 255, 255, 255),
                IM_COL32(0, 0, 0, 170), hint_rect_);
  }
}

void UiOverlay::hintBox(int width, int height, const UiOverlayState& state, float rect[4]) const {
  std::fill(rect, rect + 4, 0.0f);
  if (!context_ || state.hint.empty() || state.menu_open || !state.help.empty()) return;
  ImGui::SetCurrentContext(context_);
  ImFont* font = ImGui::GetIO().Fonts->Fonts[0];
  const HintPlace hint = hintPlace(height, state, font->FontSize * fontScale(height));
  textBoxRect(font, messageCentre(width, state), hint.y, state.hint, hint.size_px, rect);
}

void UiOverlay::drawHelp(int width, int height, const std::vector<HelpSection>& help) {
  // Sections side by side: every mode's keys first, then each mode's own.
  ImDrawList* draw = ImGui::GetForegroundDrawList();
  const float size = 0.8f * ImGui::GetFontSize(), line_h = 1.3f * size;
  const float column_w = (float(width) - 2.0f * size) / 3.0f;
  draw->AddRectFilled(ImVec2(0.0f, 0.0f), ImVec2(float(width), float(height)),
                      IM_COL32(0, 0, 0, 200));
  float x = size, y = 3.0f * size;
  for (size_t s = 0; s < help.size(); ++s) {
    const float section_h = line_h * float(help[s].lines.size() + 2);
    if (y + section_h > float(height) - size && y > 3.0f * size) {
      x += column_w;
      y = 3.0f * size;
    }
    observe(help[s].title.oneLine());
    draw->AddText(ImGui::GetFont(), 1.1f * size, ImVec2(x, y), IM_COL32(255, 210, 100, 255),
                  help[s].title.oneLine().c_str());
    y += 1.5f * line_h;
    for (const std::string& line : help[s].lines) {
      const size_t tab = line.find('\t');
      const std::string key = line.substr(0, tab);
      const std::string label = tab == std::string::npos ? "" : line.substr(tab + 1);
      observe(key);
      observe(label);
      draw->AddText(ImGui::GetFont(), size, ImVec2(x, y), IM_COL32(255, 210, 100, 255),
                    key.c_str());
      draw->AddText(ImGui::GetFont(), size, ImVec2(x + 6.0f * size, y),
                    IM_COL32(255, 255, 255, 255), label.c_str());
      y += line_h;
    }
    y += 0.5f * line_h;
  }
  observe("H / ? / Esc: close  关闭");
  draw->AddText(ImGui::GetFont(), size, ImVec2(size, float(height) - 1.5f * size),
                IM_COL32(200, 200, 200, 255), "H / ? / Esc: close  关闭");
}

}  // namespace cb

namespace cb {

void UiOverlay::labelRect(const UiLabel& label, float rect[4]) const {
  rect[0] = rect[2] = label.x, rect[1] = rect[3] = label.y;
  if (!context_) return;
  ImGui::SetCurrentContext(context_);
  const float wrap = label.centred ? 0.0f : label.wrap_width;
  const ImVec2 size =
      ImGui::GetIO().Fonts->Fonts[0]->CalcTextSizeA(label.size_px, 1e9f, wrap, label.text.c_str());
  rect[0] = label.centred ? label.x - 0.5f * size.x : label.x;
  rect[2] = rect[0] + size.x;
  rect[3] = label.y + size.y;
}

void UiOverlay::drawLabels(int width, int height, const std::vector<UiLabel>& labels) {
  if (!ready_) return;
  last_draw_ = false;
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
    observe(label.text);
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
