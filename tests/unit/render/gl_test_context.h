// A surfaceless EGL + OpenGL 4.5 core context on llvmpipe for the renderer tests: created once
// per test binary and kept current.
#pragma once

#include <string>

#include <gtest/gtest.h>

#include "app/render/gl/egl_context.h"

namespace cb {

inline bool ensureTestGlContext(std::string* error) {
  static EglContext ctx;
  static std::string failure;
  static bool tried = false;
  if (!tried) {
    tried = true;
    if (!createSurfacelessContext(&ctx, &failure)) ctx = EglContext{};
  }
  *error = failure;
  return ctx.context != EGL_NO_CONTEXT;
}

// Use at the top of a GL test: a missing context is a failure, not a skip.
#define CB_REQUIRE_GL()                                            \
  do {                                                             \
    std::string gl_error;                                          \
    ASSERT_TRUE(::cb::ensureTestGlContext(&gl_error)) << gl_error; \
  } while (0)

}  // namespace cb
