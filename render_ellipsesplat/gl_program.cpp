#include "gl_program.h"

#include <stdexcept>
#include <vector>

namespace splat {
namespace {

std::string shaderLog(GLuint shader)
{
    GLint length = 0;
    glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::vector<char> log(std::max(length, 1), '\0');
    glGetShaderInfoLog(shader, length, nullptr, log.data());
    return log.data();
}

GLuint compile(const std::string &programName, GLenum stage, const shaders::ShaderSource &source)
{
    GLuint shader = glCreateShader(stage);
    glShaderSource(shader, 1, &source.text, nullptr);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (ok != GL_TRUE) {
        std::string log = shaderLog(shader);
        glDeleteShader(shader);
        throw std::runtime_error(programName + (stage == GL_VERTEX_SHADER ? " vertex" : " fragment") +
                                 " shader does not compile (source strings " +
                                 source.sourceStrings + "):\n" + log);
    }
    return shader;
}

} // namespace

GlProgram::GlProgram(const std::string &name, const shaders::ShaderSource &vertexSource,
                     const shaders::ShaderSource &fragmentSource)
{
    GLuint vertex = compile(name, GL_VERTEX_SHADER, vertexSource);
    GLuint fragment = 0;
    try {
        fragment = compile(name, GL_FRAGMENT_SHADER, fragmentSource);
    } catch (...) {
        glDeleteShader(vertex);
        throw;
    }
    program = glCreateProgram();
    glAttachShader(program, vertex);
    glAttachShader(program, fragment);
    glLinkProgram(program);
    glDeleteShader(vertex);
    glDeleteShader(fragment);

    GLint ok = GL_FALSE;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (ok != GL_TRUE) {
        GLint length = 0;
        glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
        std::vector<char> log(std::max(length, 1), '\0');
        glGetProgramInfoLog(program, length, nullptr, log.data());
        glDeleteProgram(program);
        throw std::runtime_error(name + " program does not link:\n" + std::string(log.data()));
    }
}

GlProgram::~GlProgram()
{
    glDeleteProgram(program);
}

} // namespace splat
