// The visit in progress, on the disk: `<data dir>/unsaved-visit` names the journal of the
// visitor painting now. It is written when their journal opens and removed once the visit ended
// and their cloud went to the gallery (or the kiosk stopped and kept it). Found at the next
// start, it means the kiosk was killed (kill -9, a crash, a power cut) in the middle of that
// visit: the kiosk replays the journal into the gallery.
//
// Exactly once: before saving, the record is rewritten with the newest gallery entry's number;
// a start that finds a newer entry than that knows the save finished (a kill between the save
// and the removal) and only removes the record. Each step is written atomically and the folder
// synced, so a power cut leaves one state or the other.
//
// The file is a few lines of "key = value": journal (the journal's file name under sessions/)
// and, while the cloud is being saved, gallery_newest_before.
#pragma once

#include <optional>
#include <string>

namespace cb {

struct UnsavedVisit {
  std::string journal;                        // file name under <data dir>/sessions/
  std::optional<long> gallery_newest_before;  // set while its cloud is being saved (0: none)
};

std::string unsavedVisitPath(const std::string& data_dir);

// Writes the record atomically. False with *error naming the file.
bool writeUnsavedVisit(const std::string& data_dir, const UnsavedVisit& visit, std::string* error);
// nullopt when there is none; with *error ("FILE:LINE: what") when it cannot be read or parsed.
std::optional<UnsavedVisit> readUnsavedVisit(const std::string& data_dir, std::string* error);
// Removes the record and syncs the folder. False with *error naming the file.
bool clearUnsavedVisit(const std::string& data_dir, std::string* error);

}  // namespace cb
