// What `cloudbrush study check` prints about a protocol: stages, tutorial steps with their
// checks, tasks with time limits and what they save, the first cycle of task orders, the
// questionnaire and constructs; and the files it names that are missing.
#pragma once

#include <string>
#include <vector>

#include "app/study/protocol.h"

namespace cb {

std::string studyProtocolSummary(const StudyProtocol& protocol);

// The tutorial-check vocabulary (tutorial_condition.h), one variable a line.
std::string tutorialVocabularyText();

// Image and video files the protocol names that do not exist, each "FIELD: PATH".
std::vector<std::string> missingProtocolFiles(const StudyProtocol& protocol);

}  // namespace cb
