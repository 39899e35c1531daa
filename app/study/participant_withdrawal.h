// Withdrawal: delete everything of one participant id under a study data directory,
// and say what was deleted. What belongs to participant ID:
//   - every file or folder (at any depth) whose name is ID, or starts with ID followed by
//     '_', '-' or '.' (session folders P03_2026-11-02/, P03.cbj; P3 never matches P30);
//   - in every *.csv file under the directory, and in the key file when given: the rows whose
//     `participant` column is ID, or whose `session` column is a name of the kind above (the
//     study exports tag rows with the session id). A CSV whose records cannot be split (an
//     unclosed quote) is refused, naming file and line, before anything is deleted.
// Ids are letters, digits, '_' and '-' only. An id that matches nothing is refused. Files are
// rewritten through a temporary file and a rename, so a crash leaves the old or the new file.
// After deleting, the remaining text files are searched for the id as a whole word; those that
// still mention it (e.g. an InkML export) are listed so the operator can deal with them.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace cb {

class WithdrawalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct CsvRowRemoval {
  std::filesystem::path file;
  int rows = 0;
};

struct WithdrawalResult {
  std::vector<std::filesystem::path> removed_paths;  // files and folders, as found
  std::vector<CsvRowRemoval> removed_rows;
  std::vector<std::filesystem::path> still_mentioning;  // text files naming the id afterwards
};

// `key_file` may be empty. With `dry_run` nothing is changed and the result says what would be.
WithdrawalResult withdrawParticipant(const std::filesystem::path& data_dir,
                                     const std::string& participant,
                                     const std::filesystem::path& key_file, bool dry_run);

}  // namespace cb
