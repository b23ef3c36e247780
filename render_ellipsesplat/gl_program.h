#pragma once
// A linked GLSL program built from vertex + fragment source, with uniform lookup by name.
// Compilation or link errors throw std::runtime_error carrying the driver's log.

#include <GL/glew.h>

#include <string>

namespace splat {

class GlProgram
{
public:
    GlProgram(const std::string &name, const std::string &vertexSource, const std::string &fragmentSource);
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
