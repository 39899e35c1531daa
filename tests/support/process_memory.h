// Where a process's resident memory is, read from /proc/self/smaps and glibc's malloc: for the
// kiosk soak's per-reset breakdown (which part of VmRSS moves between visits).
#pragma once

#include <string>
#include <vector>

namespace cb::test {

struct ResidentMapping {
  long rss_kb = 0;
  long size_kb = 0;
  std::string perms;  // "rw-p", "r-xp", ...
  std::string name;   // "[heap]", a file, or "" for anonymous
};

struct ProcessMemory {
  long rss_kb = 0;        // the sum of Rss: over all mappings
  long heap_kb = 0;       // [heap]: the main arena (brk)
  long anon_kb = 0;       // anonymous, writable, not executable: mmap'd blocks, thread arenas
  long anon_exec_kb = 0;  // anonymous and executable: JIT code
  long file_kb = 0;       // file-backed (libraries, fonts, the shader cache)
  long stack_kb = 0;      // [stack] and the other named specials
  int anon_mappings = 0;
  std::vector<ResidentMapping> largest;  // the biggest by Rss, most first
  // glibc (mallinfo2, summed over all arenas; malloc_info for the arena count)
  long malloc_arena_kb = 0;   // bytes the arenas got from the system (brk and arena heaps)
  long malloc_mmap_kb = 0;    // blocks served by mmap of their own
  long malloc_in_use_kb = 0;  // allocated in arenas
  long malloc_free_kb = 0;    // free in arenas
  int malloc_arenas = 0;
};

// Reads /proc/self/smaps; `largest` keeps the `keep` biggest mappings by Rss.
ProcessMemory readProcessMemory(int keep = 6);
// One line: "rss 311.0 heap 12.1 anon 250.3 (41 maps) jit 3.1 file 40.2 | malloc arena 30.2 ...".
std::string describe(const ProcessMemory& m);

}  // namespace cb::test
