// Text of CSV fields (RFC 4180): quoting, and numbers written so that reading them back gives the
// same value bit for bit (doubles with 17 significant digits, floats with 9; times as exact
// decimals of nanoseconds; NaN, Inf and -Inf as R and pandas spell them). Missing values are
// written as NA, which R and pandas read as missing. Text is made valid UTF-8 (utf8_text.h).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace cb {

inline constexpr const char* kCsvMissing = "NA";

// The field as is when it has no comma, quote, CR or LF; else in double quotes with quotes doubled.
std::string csvField(const std::string& text);
// "" becomes NA.
std::string csvFieldOrMissing(const std::string& text);
std::string csvDouble(double v);
std::string csvFloat(float v);
std::string csvOptional(const std::optional<double>& v);  // NA when empty
// `ns` nanoseconds as an exact decimal number of seconds ("-0.000000001", "12.500000000").
std::string decimalSecondsFromNs(int64_t ns);
// `ns` nanoseconds as an exact decimal number of milliseconds ("12.500000").
std::string decimalMillisecondsFromNs(int64_t ns);

}  // namespace cb
