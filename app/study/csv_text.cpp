#include "app/study/csv_text.h"

#include <cmath>
#include <cstdio>

#include "app/study/utf8_text.h"

namespace cb {
namespace {

// |ns| split at `digits` decimal places, with the sign in front.
std::string exactDecimal(int64_t ns, int64_t unit, int digits) {
  const bool negative = ns < 0;
  // Magnitude without overflow for INT64_MIN.
  const uint64_t magnitude = negative ? uint64_t(0) - uint64_t(ns) : uint64_t(ns);
  char text[48];
  std::snprintf(text, sizeof text, "%s%llu.%0*llu", negative ? "-" : "",
                static_cast<unsigned long long>(magnitude / uint64_t(unit)), digits,
                static_cast<unsigned long long>(magnitude % uint64_t(unit)));
  return text;
}

}  // namespace

std::string csvField(const std::string& raw) {
  const std::string text = validUtf8(raw);
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  return quoted + "\"";
}

std::string csvFieldOrMissing(const std::string& text) {
  return text.empty() ? kCsvMissing : csvField(text);
}

std::string csvDouble(double v) {
  if (std::isnan(v)) return "NaN";
  if (std::isinf(v)) return v > 0 ? "Inf" : "-Inf";
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

std::string csvFloat(float v) {
  if (!std::isfinite(v)) return csvDouble(double(v));
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", double(v));
  return text;
}

std::string csvOptional(const std::optional<double>& v) {
  return v ? csvDouble(*v) : kCsvMissing;
}

std::string decimalSecondsFromNs(int64_t ns) {
  return exactDecimal(ns, 1000000000, 9);
}
std::string decimalMillisecondsFromNs(int64_t ns) {
  return exactDecimal(ns, 1000000, 6);
}

}  // namespace cb
