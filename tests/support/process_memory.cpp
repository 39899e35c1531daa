#include "tests/support/process_memory.h"

#include <malloc.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

namespace cb::test {

ProcessMemory readProcessMemory(int keep) {
  ProcessMemory m;
  std::ifstream in("/proc/self/smaps");
  std::string line;
  ResidentMapping current;
  bool have = false;
  const auto close = [&]() {
    if (!have) return;
    const bool exec = current.perms.size() > 2 && current.perms[2] == 'x';
    m.rss_kb += current.rss_kb;
    if (current.name == "[heap]")
      m.heap_kb += current.rss_kb;
    else if (current.name.empty() || current.name.rfind("[anon:", 0) == 0) {
      (exec ? m.anon_exec_kb : m.anon_kb) += current.rss_kb;
      ++m.anon_mappings;
    } else if (current.name[0] == '[')
      m.stack_kb += current.rss_kb;
    else
      m.file_kb += current.rss_kb;
    m.largest.push_back(current);
    std::sort(
        m.largest.begin(), m.largest.end(),
        [](const ResidentMapping& a, const ResidentMapping& b) { return a.rss_kb > b.rss_kb; });
    if (int(m.largest.size()) > keep) m.largest.resize(size_t(keep));
  };
  while (std::getline(in, line)) {
    // A mapping's header: "start-end perms offset dev inode [name]"; its fields: "Key: value kB".
    const size_t colon = line.find(':');
    const size_t space = line.find(' ');
    if (colon == std::string::npos || (space != std::string::npos && space < colon)) {
      close();
      current = ResidentMapping{};
      have = true;
      std::istringstream header(line);
      std::string range, offset, dev, inode;
      header >> range >> current.perms >> offset >> dev >> inode;
      std::getline(header, current.name);
      current.name.erase(0, current.name.find_first_not_of(' '));
      const size_t dash = range.find('-');
      current.size_kb = long((std::strtoull(range.c_str() + dash + 1, nullptr, 16) -
                              std::strtoull(range.c_str(), nullptr, 16)) /
                             1024);
    } else if (line.rfind("Rss:", 0) == 0) {
      current.rss_kb = std::atol(line.c_str() + 4);
    }
  }
  close();
  const struct mallinfo2 mi = mallinfo2();
  m.malloc_arena_kb = long(mi.arena / 1024);
  m.malloc_mmap_kb = long(mi.hblkhd / 1024);
  m.malloc_in_use_kb = long(mi.uordblks / 1024);
  m.malloc_free_kb = long(mi.fordblks / 1024);
  char* text = nullptr;
  size_t text_size = 0;
  if (FILE* f = open_memstream(&text, &text_size)) {
    malloc_info(0, f);
    std::fclose(f);
    for (const char* p = text; (p = std::strstr(p, "<heap nr=")) != nullptr; ++p) ++m.malloc_arenas;
    std::free(text);
  }
  return m;
}

std::string describe(const ProcessMemory& m) {
  char buffer[512];
  std::snprintf(buffer, sizeof buffer,
                "rss %.1f: heap %.1f anon %.1f (%d maps) jit %.1f file %.1f other %.1f | malloc "
                "arenas %d: system %.1f in use %.1f free %.1f, mmapped %.1f MB",
                m.rss_kb / 1024.0, m.heap_kb / 1024.0, m.anon_kb / 1024.0, m.anon_mappings,
                m.anon_exec_kb / 1024.0, m.file_kb / 1024.0, m.stack_kb / 1024.0, m.malloc_arenas,
                m.malloc_arena_kb / 1024.0, m.malloc_in_use_kb / 1024.0, m.malloc_free_kb / 1024.0,
                m.malloc_mmap_kb / 1024.0);
  std::string s = buffer;
  s += " | largest:";
  for (const ResidentMapping& r : m.largest) {
    std::snprintf(buffer, sizeof buffer, " %.1f/%.1f %s %s;", r.rss_kb / 1024.0, r.size_kb / 1024.0,
                  r.perms.c_str(), r.name.empty() ? "anon" : r.name.c_str());
    s += buffer;
  }
  return s;
}

}  // namespace cb::test
