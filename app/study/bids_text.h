// The text of BIDS tabular files and their JSON sidecars (BIDS specification 1.9, "Common
// principles: tabular files"): tab-separated values with a header row, "n/a" for a missing
// value, and a sidecar that describes every column (its description, units, and the meaning of
// each level a categorical column takes). One column table per file kind, so the TSV header and
// its description cannot drift apart.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "app/study/export_columns.h"

namespace cb {

inline constexpr const char* kBidsMissing = "n/a";

struct BidsColumn {
  std::string name;
  std::string description;
  std::string units;  // empty: dimensionless or text (no "Units" key)
  std::vector<std::pair<std::string, std::string>> levels;  // value → meaning (categorical)
};

// An exported table's columns (export_columns.h) as BIDS describes them: the unit only when it
// is one BIDS takes (bidsUnit), "NA" in the text as BIDS writes a missing value, "n/a".
std::vector<BidsColumn> bidsColumnsOf(const std::vector<ExportColumn>& table);
// The text with every word "NA" made "n/a".
std::string bidsMissingWords(const std::string& text);

// The header row: the columns' names joined by tabs, then a newline.
std::string bidsTsvHeader(const std::vector<BidsColumn>& columns);
// The sidecar: {"name": {"Description": ..., "Units": ..., "Levels": {...}}, ...}, indented.
std::string bidsColumnsJson(const std::vector<BidsColumn>& columns);

// A text value for a TSV cell: valid UTF-8, tabs and line breaks made spaces; "" becomes n/a.
std::string bidsTsvText(const std::string& text);
// A double that reads back bit for bit (csv_text.h); n/a when empty or not finite.
std::string bidsTsvNumber(const std::optional<double>& value);
// `ns` nanoseconds as exact decimal seconds ("12.500000000").
std::string bidsSeconds(int64_t ns);

// A BIDS entity label: the ASCII letters and digits of `text` ("P01-2026..." → "P012026...").
std::string bidsLabel(const std::string& text);

// Pretty JSON object text from already formatted "key": value members, one per line.
std::string bidsJsonObject(const std::vector<std::pair<std::string, std::string>>& members);

}  // namespace cb
