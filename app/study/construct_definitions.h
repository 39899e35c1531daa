// Constructs: named groups of questionnaire items summarised together (likert_statistics.h).
// Declared in a TOML file, one [[construct]] table each:
//
//   [[construct]]
//   name = "Paint style"
//   items = ["Q1", "Q2", "Q3", "Q4", "Q5", "Q6"]
//
// Errors name the file, the construct's position and the field. Without a file, the report uses
// the three sections of the thesis's questionnaire (Appendix C): "Paint style" Q1–Q6, "Cloud
// drawing" Q7–Q18, "System use" Q19–Q27. These are the questionnaire's own headings, not the
// constructs of the thesis's Table 7.3, whose item groups the thesis does not give.
#pragma once

#include <string>
#include <vector>

#include "app/study/likert_statistics.h"

namespace cb {

std::vector<ConstructDefinition> appendixCSections();
std::vector<ConstructDefinition> loadConstructDefinitions(const std::string& path);

}  // namespace cb
