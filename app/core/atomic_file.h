// Replacing a file so that a reader, a crash or a power cut sees either the old or the new
// content, never a torn one: write a temporary file in the same folder (rename is atomic only
// within one file system), fsync it, rename it over the target, fsync the folder (so the new
// directory entry is on the disk too). The one writer every export and session file uses.
#pragma once

#include <string>
#include <string_view>

namespace cb {

// Writes `content` to `path` atomically. False with *error (when not null) naming the file, the
// step and the errno text (the folder does not exist, the disk is full, ...); the temporary is
// removed and `path` keeps what it had.
bool writeFileAtomically(const std::string& path, std::string_view content, std::string* error);

// fsync of the folder holding `path` (after a file or folder was renamed into it; "DIR/." names
// DIR itself). False with *error naming the folder.
bool syncFolderOf(const std::string& path, std::string* error);

// For code that writes a file by its path (OpenVDB, OpenEXR, libpng, a stream): write the whole
// file at tempPath(), then commit(). A replacement not committed (an error, an exception) removes
// its temporary when it goes out of scope, leaving `path` as it was.
//
//   AtomicFileReplacement out(path);
//   library.write(out.tempPath());
//   if (!out.commit(&error)) ...
class AtomicFileReplacement {
 public:
  explicit AtomicFileReplacement(std::string path);
  ~AtomicFileReplacement();
  AtomicFileReplacement(const AtomicFileReplacement&) = delete;
  AtomicFileReplacement& operator=(const AtomicFileReplacement&) = delete;

  // "<path>.tmp.<pid>.<n>": unique per process and replacement, in the target's folder.
  const std::string& tempPath() const { return temp_; }
  const std::string& path() const { return path_; }
  // fsyncs the temporary, renames it over path(), fsyncs the folder. False with *error; the
  // temporary is then removed.
  bool commit(std::string* error);

 private:
  std::string path_;
  std::string temp_;
  bool done_ = false;
};

}  // namespace cb
