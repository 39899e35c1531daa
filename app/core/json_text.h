// JSON text for the small files the program writes by hand (session.json, health.json): a string
// quoted and escaped as RFC 8259 §7 requires (quote, backslash and control characters).
#pragma once

#include <string>

namespace cb {

// `text` as a JSON string literal, quotes included. Bytes ≥ 0x80 pass through unchanged, so
// UTF-8 stays UTF-8.
std::string jsonString(const std::string& text);

}  // namespace cb
