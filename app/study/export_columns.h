// What every column of the study's tables means, written once: the CSV writers' header lines
// (trials.csv, strokes.csv, samples.csv, events.csv), codebook.csv and the BIDS sidecars
// (beh.json, events.json, the motion channels.tsv) all read these tables, so a column cannot be
// described twice or differently.
//
//   name         the column's header
//   type         integer | number | text | category
//   unit         s, ns, ms, mm, mm/s, deg (SI or SI-derived: BIDS takes these as Units), or a
//                count's or code's description ("device units", "fraction 0..1", "0/1", ...),
//                or "" where none applies
//   description  what it is and how it was made
//   levels       a category's values and their meaning
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace cb {

struct ExportColumn {
  std::string name, type, unit, description;
  std::vector<std::pair<std::string, std::string>> levels;
};

// The columns of each table, in the order its writer writes them.
const std::vector<ExportColumn>& trialColumns();   // trials.csv, and BIDS _beh.tsv
const std::vector<ExportColumn>& strokeColumns();  // strokes.csv
const std::vector<ExportColumn>& sampleColumns();  // samples.csv
const std::vector<ExportColumn>& eventColumns();   // events.csv
// BIDS _events.tsv (a row per stage and operator pause; task rows carry their trial's columns,
// described by trialColumns() with "For task rows, " before them).
const std::vector<ExportColumn>& bidsEventColumns();

// The column `name` of `table`; throws std::out_of_range naming it when there is none.
const ExportColumn& exportColumn(const std::vector<ExportColumn>& table, const std::string& name);

// "a,b,c\n": a CSV header line of the table's names.
std::string csvHeaderLine(const std::vector<ExportColumn>& table);

// The unit as BIDS Units take it: s, ns, ms, mm, mm/s, deg; "" for the others.
std::string bidsUnit(const std::string& unit);

}  // namespace cb
