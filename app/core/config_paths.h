// Where configuration lives: the defaults shipped in config/ and a writable state directory
// (kiosk profiles, sessions). Both can be overridden by environment variables. Also where the
// recorded device data (tests/fixtures) is found.
#pragma once

#include <string>

namespace cb {

// CLOUDBRUSH_CONFIG_DIR, else the source tree's config/ (compiled in), else
// /usr/share/cloudbrush/config.
std::string defaultConfigDir();
// CLOUDBRUSH_STATE_DIR, else $XDG_STATE_HOME/cloudbrush, else ~/.local/state/cloudbrush.
// Created if missing.
std::string stateDir();
// defaultConfigDir()/name.
std::string configFile(const std::string& name);
// The recorded tablet HID descriptors: the source tree's tests/fixtures/hid (compiled in) if it
// exists, else /usr/share/cloudbrush/fixtures/hid.
std::string defaultHidFixtureDir();

}  // namespace cb
