#pragma once
// The one place that includes the OpenGL API. glvnd's libOpenGL exports every core 4.5 entry
// point, so prototypes are enough and no loader is needed (docs/design.md §7 fact 9).
#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/glcorearb.h>
