#pragma once
// A linked GLSL program built from vertex + fragment source, with uniform lookup by name.
// Compilation or link errors throw std::runtime_error carrying the driver's log and, for
// compilation, the files its source string numbers stand for.

#include "splat_shaders.h"

#include <GL/glew.h>

#include <string>

namespace splat {

class GlProgram
{
public:
    GlProgram(const std::string &name, const shaders::ShaderSource &vertex, const shaders::ShaderSource &fragment);
    ~GlProgram();
    GlProgram(const GlProgram &) = delete;
    GlProgram &operator=(const GlProgram &) = delete;

    GLuint id() const { return program; }
    // -1 when the uniform is unused by the shaders (GL ignores writes to -1).
    GLint uniform(const char *name) const { return glGetUniformLocation(program, name); }

private:
    GLuint program = 0;
};

} // namespace splat
