// A small file the kiosk keeps replacing (health.json, the metrics) that must go on being
// replaced when something else has filled the disk to the last byte. The new content is written
// into a spare copy, `<path>.spare`, whose blocks were taken while there was room and are kept
// (overwritten in place, never truncated below what they hold), then exchanged with `<path>` in
// one step (renameat2 RENAME_EXCHANGE): the old copy becomes the next spare, with its blocks. A
// reader sees the old content or the new, never a torn one, as with writeFileAtomically; once
// both copies exist no new block is needed while the content stays within the blocks it had.
#pragma once

#include <string>
#include <string_view>

namespace cb {

// Replaces `path` with `content` through its spare as above; where the spare cannot be used
// (the first writes, a file system without RENAME_EXCHANGE) writeFileAtomically does it. False
// with *error (when not null) naming the file, the step and the errno text.
bool writeFileKeepingBlocks(const std::string& path, std::string_view content, std::string* error);

}  // namespace cb
