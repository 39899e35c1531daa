// What the kiosk says to visitors, in the language set in config/kiosk.toml: a table per language
// in config/kiosk/texts.toml (English "en" and Chinese "zh" bundled). English must hold every key
// (kKioskTextKeys); another language may leave keys out, and a missing key falls back to English
// with one log line per key. Texts may hold placeholders such as {seconds}, filled by format().
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

namespace cb {

// Every key the kiosk uses.
inline constexpr const char* kKioskTextKeys[] = {
    "invitation",       // attract loop, big
    "invitation_hint",  // attract loop, under it
    "countdown",        // {seconds}
    "reconnect_title",  // the pen was unplugged mid-visit
    "reconnect_hint",
    "gallery_notice",    // {days}: what the gallery keeps and for how long
    "recording_notice",  // {days}: how long pen journals are kept
    "saved_notice",      // {number}: the visitor's cloud went into the gallery
    // The painter's words for the visitor (app/shell/kiosk/visitor_words.h): the status line per mode,
    "status_camera",
    "status_paint",
    "status_erase",
    // the menu's button (closed, open) and targets,
    "menu_button",
    "menu_close",
    "menu_camera",
    "menu_paint",
    "menu_erase",
    "menu_reset_view",
    "menu_rotate",
    "menu_zoom_out",
    "menu_zoom_in",
    "menu_next_brush",
    "menu_smaller",
    "menu_larger",
    "menu_good_view",
    "menu_next_eraser",
    "menu_cut",
    "menu_undo",
    "menu_redo",
    "menu_start_again",
    "menu_help",
    // the help (lines), the warning of a view edge-on to the canvas, and the answers to the
    // visitor's actions.
    "help",
    "edge_on",
    "nothing_to_undo",
    "nothing_to_redo",
    "cleared",
    "ink_lost",
    "stroke_ended",
    "rotating",
    "rotation_stopped",
    "vacuum_place",
    "vacuum_cut",
};

class KioskTexts {
 public:
  using Log = std::function<void(const std::string&)>;
  // Reads `path` and picks `language`. Throws std::runtime_error naming the file and what is
  // wrong (syntax, a non-string value, no such language, an English key missing).
  static KioskTexts load(const std::string& path, const std::string& language, Log log);

  const std::string& language() const { return language_; }
  // The text of `key` in the chosen language; English (logged once) when the language lacks it.
  std::string text(const std::string& key) const;
  // text(key) with each {name} replaced by its value.
  std::string format(const std::string& key,
                     const std::map<std::string, std::string>& values) const;
  // Every character of the chosen language's texts and English (for the font atlas).
  std::string allText() const;

 private:
  std::string language_;
  std::map<std::string, std::string> chosen_, english_;
  Log log_;
  mutable std::vector<std::string> logged_;
};

}  // namespace cb
