// The one place GL headers are included: OpenGL 4.5 core through libglvnd's libOpenGL, which
// exports every core entry point, so no loader is needed.
#pragma once

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>
