// The kiosk's malloc policy (glibc), set once at start-up before any thread starts, so the
// resident memory after each idle reset is what the next visit needs, the same after weeks as
// after the first hour (the soak, tests/unit/kiosk/kiosk_soak.cpp). Measured there per
// reset (smaps and mallinfo2, `kiosk_soak --memory-detail`), with glibc's defaults:
//  - the mmap threshold is dynamic: freeing a block of up to 32 MiB that was mmapped (a grown
//    brick pool, a frame target) raises it to that size, and so does the trim threshold (to
//    twice that). After that, blocks of megabytes go into the arenas, and the top of a thread's
//    arena stays resident (malloc_trim trims only the main arena's top): VmRSS after the resets
//    of one run rose by 1–8 MiB at a time through the hours;
//  - how many arenas there are (8, 9 or 10 in three runs of the same soak) follows contention
//    between threads, so the memory each arena holds free differs from run to run.
// A fixed threshold (glibc's default, 128 KiB: blocks above it are mmapped and unmapped on free,
// exactly), the default trim threshold kept fixed, and at most 4 arenas.
#pragma once

namespace cb {

// Returns false (and changes nothing more) if glibc refused a setting.
bool setKioskHeapPolicy();

}  // namespace cb
