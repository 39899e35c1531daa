#include "app/render/shader_program.h"

#include <algorithm>
#include <initializer_list>

#include "shaders/shader_source.h"

namespace cb {

GLuint compileShaderStage(GLenum stage, const std::vector<std::string>& files, std::string* error,
                          const std::string& defines) {
  std::vector<std::string> texts{"#version 450 core\n" + defines};
  for (const std::string& name : files) {
    std::string_view src = shaderSource(name);
    if (src.empty()) {
      *error = "shader '" + name + "' is not embedded (is it in shaders/?)";
      return 0;
    }
    std::string text(src);
    // Each file may carry its own #version line for standalone checking; keep only ours.
    if (text.rfind("#version", 0) == 0) text = "//" + text;
    texts.push_back("#line 1\n" + text + "\n");
  }
  std::vector<const char*> ptrs;
  for (const std::string& t : texts) ptrs.push_back(t.c_str());
  GLuint shader = glCreateShader(stage);
  glShaderSource(shader, GLsizei(ptrs.size()), ptrs.data(), nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    GLint len = 0;
    glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &len);
    std::string log(size_t(std::max(len, 1)), '\0');
    glGetShaderInfoLog(shader, len, nullptr, log.data());
    std::string names;
    for (const std::string& n : files) names += (names.empty() ? "" : " + ") + n;
    *error = "compiling " + names + ": " + log;
    glDeleteShader(shader);
    return 0;
  }
  return shader;
}

namespace {

// Links the compiled stages into a program (the stages are deleted either way); 0 and the info
// log in `error` on failure.
GLuint linkStages(std::initializer_list<GLuint> stages, std::string* error) {
  GLuint program = glCreateProgram();
  for (GLuint stage : stages) glAttachShader(program, stage);
  glLinkProgram(program);
  for (GLuint stage : stages) glDeleteShader(stage);
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint len = 0;
    glGetProgramiv(program, GL_INFO_LOG_LENGTH, &len);
    std::string log(size_t(std::max(len, 1)), '\0');
    glGetProgramInfoLog(program, len, nullptr, log.data());
    *error = "linking program: " + log;
    glDeleteProgram(program);
    return 0;
  }
  return program;
}

}  // namespace

GLuint linkProgram(const std::vector<std::string>& vertex_files,
                   const std::vector<std::string>& fragment_files, std::string* error,
                   const std::string& fragment_defines) {
  GLuint vs = compileShaderStage(GL_VERTEX_SHADER, vertex_files, error);
  if (!vs) return 0;
  GLuint fs = compileShaderStage(GL_FRAGMENT_SHADER, fragment_files, error, fragment_defines);
  if (!fs) {
    glDeleteShader(vs);
    return 0;
  }
  return linkStages({vs, fs}, error);
}

GLuint linkComputeProgram(const std::vector<std::string>& files, std::string* error,
                          const std::string& defines) {
  GLuint cs = compileShaderStage(GL_COMPUTE_SHADER, files, error, defines);
  return cs ? linkStages({cs}, error) : 0;
}

}  // namespace cb
