// Text from journals and answer files as valid UTF-8 for the exports (XML requires it; R and
// pandas expect it): every byte sequence that is not well-formed UTF-8 (Unicode 15, Table 3-7:
// overlong forms, surrogates and code points above U+10FFFF included) becomes U+FFFD.
#pragma once

#include <string>
#include <string_view>

namespace cb {

std::string validUtf8(std::string_view text);
// validUtf8, with & < > " ' escaped as entities valid in both XML (InkML) and HTML/SVG and
// control characters XML 1.0 forbids replaced by '?'.
std::string markupEscape(std::string_view text);

// Typing on a form (the on-screen keyboard, a physical keyboard, an input method):
// text a key typed is taken when it is valid UTF-8 without control characters (C0, DEL, C1);
// appendTyped adds it unless the field would exceed max_bytes (no character is cut), and
// eraseLastCharacter removes the last code point (all of its bytes).
bool isTypedText(std::string_view text);
bool appendTyped(std::string* field, std::string_view text, size_t max_bytes);
void eraseLastCharacter(std::string* field);

}  // namespace cb
