// Test helper: a top-level window of an X server found by its name, from a second client (the
// test's observer). Include after gtest: Xlib's macros (None, Bool, ...) would break its headers.
#pragma once

#include <X11/Xlib.h>

#include <cstring>

namespace cb {

// The first child of the root window named `wanted`, or 0.
inline Window findWindowNamed(::Display* x, const char* wanted) {
  Window root, parent, *children = nullptr;
  unsigned count = 0;
  Window found = 0;
  XQueryTree(x, DefaultRootWindow(x), &root, &parent, &children, &count);
  for (unsigned i = 0; i < count && !found; ++i) {
    char* name = nullptr;
    if (XFetchName(x, children[i], &name) && name) {
      if (std::strcmp(name, wanted) == 0) found = children[i];
      XFree(name);
    }
  }
  if (children) XFree(children);
  return found;
}

}  // namespace cb
