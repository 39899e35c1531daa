// Compiling and linking GLSL programs from the embedded shaders (shaders/), with the info log in
// the error message.
#pragma once

#include <string>
#include <vector>

#include "app/render/gl/gl.h"

namespace cb {

// Compiles one stage from the concatenation of `#version 450 core` and the named embedded
// shader files (so a shading stage can be linked in front of the ray caster). Returns 0 and
// fills `error` on failure.
// `defines` (e.g. "#define CB_SKIP 1\n") go right after the #version line.
GLuint compileShaderStage(GLenum stage, const std::vector<std::string>& files, std::string* error,
                          const std::string& defines = "");
// Links a program from a vertex and a fragment stage, each assembled as above.
GLuint linkProgram(const std::vector<std::string>& vertex_files,
                   const std::vector<std::string>& fragment_files, std::string* error,
                   const std::string& fragment_defines = "");
// Links a compute program from one stage assembled as above.
GLuint linkComputeProgram(const std::vector<std::string>& files, std::string* error,
                          const std::string& defines = "");

}  // namespace cb
