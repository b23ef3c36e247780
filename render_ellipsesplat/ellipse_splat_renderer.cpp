#include "ellipse_splat_renderer.h"

#include "gl_program.h"
#include "splat_shaders.h"

#include <Eigen/Dense>

#include <cstddef>
#include <stdexcept>

namespace splat {
namespace {

using Matrix4 = Eigen::Matrix4f; // column-major, like OpenGL

struct SplatVertex // one per splat, read with divisor 1
{
    float center[3];
    float normal[3];
    float majorAxis[3];
    float minorAxis[3];
    std::uint8_t color[4];
};

Eigen::Matrix3f normalMatrixOf(const float modelView[16])
{
    return Eigen::Map<const Matrix4>(modelView).topLeftCorner<3, 3>().inverse().transpose();
}

void setLightingUniforms(const GlProgram &program, const Lighting &lighting)
{
    glUniform3fv(program.uniform("towardsLight"), 1, lighting.towardsLight);
    glUniform3fv(program.uniform("lightAmbient"), 1, lighting.ambient);
    glUniform3fv(program.uniform("lightDiffuse"), 1, lighting.diffuse);
    glUniform3fv(program.uniform("lightSpecular"), 1, lighting.specular);
    glUniform1f(program.uniform("shininess"), lighting.shininess);
}

void setCameraUniforms(const GlProgram &program, const float projection[16], const Viewport &viewport)
{
    const Matrix4 inverse = Eigen::Map<const Matrix4>(projection).inverse();
    glUniformMatrix4fv(program.uniform("projection"), 1, GL_FALSE, projection);
    glUniformMatrix4fv(program.uniform("inverseProjection"), 1, GL_FALSE, inverse.data());
    glUniform4f(program.uniform("viewport"), float(viewport.x), float(viewport.y), float(viewport.width),
                float(viewport.height));
}

void setModelViewUniforms(const GlProgram &program, const float modelView[16])
{
    glUniformMatrix4fv(program.uniform("modelView"), 1, GL_FALSE, modelView);
    glUniformMatrix3fv(program.uniform("normalMatrix"), 1, GL_FALSE, normalMatrixOf(modelView).data());
}

// Everything render() changes, restored on scope exit so the caller (MeshLab) keeps its state.
class ScopedGlState
{
public:
    ScopedGlState()
    {
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &drawFramebuffer);
        glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &readFramebuffer);
        glGetIntegerv(GL_VIEWPORT, viewport);
        glGetIntegerv(GL_CURRENT_PROGRAM, &program);
        glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vertexArray);
        glGetIntegerv(GL_ACTIVE_TEXTURE, &activeTexture);
        glGetIntegerv(GL_DEPTH_FUNC, &depthFunc);
        glGetIntegerv(GL_BLEND_SRC_RGB, &blendSrcRgb);
        glGetIntegerv(GL_BLEND_DST_RGB, &blendDstRgb);
        glGetIntegerv(GL_BLEND_SRC_ALPHA, &blendSrcAlpha);
        glGetIntegerv(GL_BLEND_DST_ALPHA, &blendDstAlpha);
        glGetIntegerv(GL_BLEND_EQUATION_RGB, &blendEquationRgb);
        glGetIntegerv(GL_BLEND_EQUATION_ALPHA, &blendEquationAlpha);
        glGetIntegerv(GL_POLYGON_MODE, polygonMode);
        glGetBooleanv(GL_DEPTH_WRITEMASK, &depthMask);
        glGetBooleanv(GL_COLOR_WRITEMASK, colorMask);
        for (int i = 0; i < kCapabilityCount; ++i)
            enabled[i] = glIsEnabled(kCapabilities[i]);
    }
    ~ScopedGlState()
    {
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, drawFramebuffer);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, readFramebuffer);
        glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
        glUseProgram(program);
        glBindVertexArray(vertexArray);
        glActiveTexture(activeTexture);
        glDepthFunc(depthFunc);
        glBlendFuncSeparate(blendSrcRgb, blendDstRgb, blendSrcAlpha, blendDstAlpha);
        glBlendEquationSeparate(blendEquationRgb, blendEquationAlpha);
        glPolygonMode(GL_FRONT_AND_BACK, polygonMode[0]);
        glDepthMask(depthMask);
        glColorMask(colorMask[0], colorMask[1], colorMask[2], colorMask[3]);
        for (int i = 0; i < kCapabilityCount; ++i)
            enabled[i] ? glEnable(kCapabilities[i]) : glDisable(kCapabilities[i]);
    }
    GLuint callerDrawFramebuffer() const { return GLuint(drawFramebuffer); }

private:
    static constexpr int kCapabilityCount = 5;
    static constexpr GLenum kCapabilities[kCapabilityCount] = {GL_DEPTH_TEST, GL_BLEND, GL_CULL_FACE,
                                                               GL_PROGRAM_POINT_SIZE, GL_SCISSOR_TEST};
    GLint drawFramebuffer, readFramebuffer, viewport[4], program, vertexArray, activeTexture, depthFunc;
    GLint blendSrcRgb, blendDstRgb, blendSrcAlpha, blendDstAlpha, blendEquationRgb, blendEquationAlpha;
    GLint polygonMode[2];
    GLboolean depthMask, colorMask[4];
    GLboolean enabled[kCapabilityCount];
};
constexpr GLenum ScopedGlState::kCapabilities[];

} // namespace

std::string unsupportedReason()
{
    if (!GLEW_VERSION_3_3)
        return std::string("Ellipse splatting needs OpenGL 3.3; this context offers ") +
               reinterpret_cast<const char *>(glGetString(GL_VERSION));
    return std::string();
}

// ---------------------------------------------------------------------------------------------

SplatCloud::SplatCloud(const SurfelArrays &surfels, const std::uint8_t defaultColor[4])
    : count(GLsizei(surfels.size()))
{
    const std::size_t n = surfels.size();
    if (surfels.normals.size() != 3 * n || surfels.majorAxes.size() != 3 * n || surfels.minorAxes.size() != 3 * n)
        throw std::invalid_argument("SplatCloud: every surfel needs a normal and both ellipse axes");

    std::vector<SplatVertex> vertices(n);
    for (std::size_t i = 0; i < n; ++i) {
        SplatVertex &v = vertices[i];
        for (int c = 0; c < 3; ++c) {
            v.center[c] = surfels.positions[3 * i + c];
            v.normal[c] = surfels.normals[3 * i + c];
            v.majorAxis[c] = surfels.majorAxes[3 * i + c];
            v.minorAxis[c] = surfels.minorAxes[3 * i + c];
        }
        for (int c = 0; c < 4; ++c)
            v.color[c] = surfels.hasColors() ? surfels.colors[4 * i + c] : defaultColor[c];
    }

    GLint previousVao = 0;
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &previousVao);
    glGenBuffers(1, &buffer);
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glBindBuffer(GL_ARRAY_BUFFER, buffer);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(n * sizeof(SplatVertex)), vertices.data(), GL_STATIC_DRAW);

    auto attribute = [](GLuint location, GLint components, GLenum type, GLboolean normalized, std::size_t offset) {
        glEnableVertexAttribArray(location);
        glVertexAttribPointer(location, components, type, normalized, sizeof(SplatVertex),
                              reinterpret_cast<const void *>(offset));
        glVertexAttribDivisor(location, 1);
    };
    attribute(shaders::kCenter, 3, GL_FLOAT, GL_FALSE, offsetof(SplatVertex, center));
    attribute(shaders::kNormal, 3, GL_FLOAT, GL_FALSE, offsetof(SplatVertex, normal));
    attribute(shaders::kMajorAxis, 3, GL_FLOAT, GL_FALSE, offsetof(SplatVertex, majorAxis));
    attribute(shaders::kMinorAxis, 3, GL_FLOAT, GL_FALSE, offsetof(SplatVertex, minorAxis));
    attribute(shaders::kColor, 4, GL_UNSIGNED_BYTE, GL_TRUE, offsetof(SplatVertex, color));

    glBindVertexArray(GLuint(previousVao));
    glBindBuffer(GL_ARRAY_BUFFER, 0);
}

SplatCloud::~SplatCloud()
{
    glDeleteVertexArrays(1, &vao);
    glDeleteBuffers(1, &buffer);
}

// ---------------------------------------------------------------------------------------------

// Float render targets of passes 1-2, sized to the viewport and reallocated when it changes.
struct EllipseSplatRenderer::AccumulationTargets
{
    AccumulationTargets(int width, int height) : width(width), height(height)
    {
        glGenFramebuffers(1, &framebuffer);
        glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
        GLuint *textures[2] = {&colorSums, &normalDepthSums};
        for (int i = 0; i < 2; ++i) {
            glGenTextures(1, textures[i]);
            glBindTexture(GL_TEXTURE_2D, *textures[i]);
            glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, width, height, 0, GL_RGBA, GL_FLOAT, nullptr);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
            glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + i, GL_TEXTURE_2D, *textures[i], 0);
        }
        glBindTexture(GL_TEXTURE_2D, 0);
        glGenRenderbuffers(1, &depth);
        glBindRenderbuffer(GL_RENDERBUFFER, depth);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, width, height);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
        const GLenum drawBuffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
        glDrawBuffers(2, drawBuffers);
        const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
        if (status != GL_FRAMEBUFFER_COMPLETE) {
            release();
            throw std::runtime_error("Ellipse splatting: float render targets are not supported (framebuffer status " +
                                     std::to_string(status) + ")");
        }
    }
    ~AccumulationTargets() { release(); }
    void release()
    {
        glDeleteFramebuffers(1, &framebuffer);
        glDeleteTextures(1, &colorSums);
        glDeleteTextures(1, &normalDepthSums);
        glDeleteRenderbuffers(1, &depth);
        framebuffer = colorSums = normalDepthSums = depth = 0;
    }

    int width, height;
    GLuint framebuffer = 0, colorSums = 0, normalDepthSums = 0, depth = 0;
};

EllipseSplatRenderer::EllipseSplatRenderer()
{
    const std::string reason = unsupportedReason();
    if (!reason.empty())
        throw std::runtime_error(reason);
    visibilityProgram.reset(new GlProgram("visibility", shaders::splatVertex(), shaders::visibilityFragment()));
    accumulationProgram.reset(new GlProgram("accumulation", shaders::splatVertex(), shaders::accumulationFragment()));
    normalizationProgram.reset(
        new GlProgram("normalization", shaders::normalizationVertex(), shaders::normalizationFragment()));
    opaqueProgram.reset(new GlProgram("opaque splat", shaders::splatVertex(), shaders::opaqueFragment()));
    pointProgram.reset(new GlProgram("point", shaders::pointVertex(), shaders::pointFragment()));

    // One triangle covering the screen (cheaper and seamless compared to a two-triangle quad).
    const float screenTriangle[6] = {-1.0f, -1.0f, 3.0f, -1.0f, -1.0f, 3.0f};
    GLint previousVao = 0;
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &previousVao);
    glGenBuffers(1, &screenTriangleBuffer);
    glGenVertexArrays(1, &screenTriangleVao);
    glBindVertexArray(screenTriangleVao);
    glBindBuffer(GL_ARRAY_BUFFER, screenTriangleBuffer);
    glBufferData(GL_ARRAY_BUFFER, sizeof(screenTriangle), screenTriangle, GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, nullptr);
    glBindVertexArray(GLuint(previousVao));
    glBindBuffer(GL_ARRAY_BUFFER, 0);
}

EllipseSplatRenderer::~EllipseSplatRenderer()
{
    glDeleteVertexArrays(1, &screenTriangleVao);
    glDeleteBuffers(1, &screenTriangleBuffer);
}

void EllipseSplatRenderer::render(const std::vector<SplatDrawItem> &items, const float projection[16],
                                  const Viewport &viewport, const Lighting &lighting, const SplatSettings &settings)
{
    if (viewport.width <= 0 || viewport.height <= 0)
        return;
    ScopedGlState savedState;
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glDisable(GL_CULL_FACE);
    glDisable(GL_SCISSOR_TEST);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glViewport(viewport.x, viewport.y, viewport.width, viewport.height);

    switch (settings.mode) {
    case SplatMode::ThreePass:
        renderThreePasses(items, projection, viewport, lighting, settings, savedState.callerDrawFramebuffer());
        break;
    case SplatMode::OnePassOpaque:
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
        glDisable(GL_BLEND);
        drawSplats(*opaqueProgram, items, projection, viewport, lighting, settings);
        break;
    case SplatMode::Points:
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
        glDisable(GL_BLEND);
        drawPoints(items, projection, lighting, settings);
        break;
    }
}

void EllipseSplatRenderer::renderThreePasses(const std::vector<SplatDrawItem> &items, const float projection[16],
                                             const Viewport &viewport, const Lighting &lighting,
                                             const SplatSettings &settings, GLuint callerFramebuffer)
{
    if (!targets || targets->width != viewport.width || targets->height != viewport.height) {
        targets.reset(); // free the old targets before allocating the new ones
        targets.reset(new AccumulationTargets(viewport.width, viewport.height));
    }
    const Viewport targetViewport{0, 0, viewport.width, viewport.height};
    glBindFramebuffer(GL_FRAMEBUFFER, targets->framebuffer);
    glViewport(0, 0, viewport.width, viewport.height);
    const float zeros[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    const float farthest = 1.0f;
    glDepthMask(GL_TRUE);
    glClearBufferfv(GL_COLOR, 0, zeros);
    glClearBufferfv(GL_COLOR, 1, zeros);
    glClearBufferfv(GL_DEPTH, 0, &farthest);
    glEnable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);

    // Pass 1: the visible surface, pushed back by ε, in the depth buffer only.
    if (settings.visibilityPass) {
        glDepthFunc(GL_LESS);
        glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        drawSplats(*visibilityProgram, items, projection, targetViewport, lighting, settings);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    }

    // Pass 2: add up every splat fragment in front of that offset surface.
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    drawSplats(*accumulationProgram, items, projection, targetViewport, lighting, settings);

    // Pass 3: normalise, light, and write colour and depth into the caller's framebuffer.
    glBindFramebuffer(GL_FRAMEBUFFER, callerFramebuffer);
    glViewport(viewport.x, viewport.y, viewport.width, viewport.height);
    glDisable(GL_BLEND);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    const GlProgram &program = *normalizationProgram;
    glUseProgram(program.id());
    setCameraUniforms(program, projection, viewport);
    setLightingUniforms(program, lighting);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, targets->colorSums);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, targets->normalDepthSums);
    glUniform1i(program.uniform("colorSums"), 0);
    glUniform1i(program.uniform("normalDepthSums"), 1);
    glBindVertexArray(screenTriangleVao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindTexture(GL_TEXTURE_2D, 0);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, 0);
}

void EllipseSplatRenderer::drawSplats(const GlProgram &program, const std::vector<SplatDrawItem> &items,
                                      const float projection[16], const Viewport &viewport,
                                      const Lighting &lighting, const SplatSettings &settings)
{
    glUseProgram(program.id());
    setCameraUniforms(program, projection, viewport);
    setLightingUniforms(program, lighting);
    glUniform1f(program.uniform("splatScale"), settings.splatScale);
    glUniform1f(program.uniform("depthOffsetFactor"), settings.depthOffsetFactor);
    glUniform1i(program.uniform("cullBackFaces"), settings.cullBackFaces ? 1 : 0);
    for (const SplatDrawItem &item : items) {
        setModelViewUniforms(program, item.modelView);
        glBindVertexArray(item.cloud->vertexArray());
        glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, item.cloud->size());
    }
}

void EllipseSplatRenderer::drawPoints(const std::vector<SplatDrawItem> &items, const float projection[16],
                                      const Lighting &lighting, const SplatSettings &settings)
{
    const GlProgram &program = *pointProgram;
    glEnable(GL_PROGRAM_POINT_SIZE);
    glUseProgram(program.id());
    glUniformMatrix4fv(program.uniform("projection"), 1, GL_FALSE, projection);
    glUniform1f(program.uniform("pointSize"), settings.pointSize);
    setLightingUniforms(program, lighting);
    for (const SplatDrawItem &item : items) {
        setModelViewUniforms(program, item.modelView);
        glBindVertexArray(item.cloud->vertexArray());
        // The attributes advance per instance, so each instance is one point.
        glDrawArraysInstanced(GL_POINTS, 0, 1, item.cloud->size());
    }
}

// ---------------------------------------------------------------------------------------------

ShadedMeshRenderer::ShadedMeshRenderer(const std::vector<float> &positions, const std::vector<float> &normals,
                                       const std::vector<std::uint8_t> &colors,
                                       const std::vector<unsigned> &triangleIndices,
                                       const std::uint8_t defaultColor[4])
    : program(new GlProgram("shaded mesh", shaders::meshVertex(), shaders::meshFragment())),
      indexCount(GLsizei(triangleIndices.size()))
{
    struct MeshVertex
    {
        float position[3];
        float normal[3];
        std::uint8_t color[4];
    };
    const std::size_t n = positions.size() / 3;
    const bool hasNormals = normals.size() == positions.size();
    const bool hasColors = colors.size() == 4 * n;
    std::vector<MeshVertex> vertices(n);
    for (std::size_t i = 0; i < n; ++i) {
        for (int c = 0; c < 3; ++c) {
            vertices[i].position[c] = positions[3 * i + c];
            vertices[i].normal[c] = hasNormals ? normals[3 * i + c] : 0.0f;
        }
        for (int c = 0; c < 4; ++c)
            vertices[i].color[c] = hasColors ? colors[4 * i + c] : defaultColor[c];
    }

    GLint previousVao = 0;
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &previousVao);
    glGenBuffers(2, buffers);
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glBindBuffer(GL_ARRAY_BUFFER, buffers[0]);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(n * sizeof(MeshVertex)), vertices.data(), GL_STATIC_DRAW);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, buffers[1]);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(triangleIndices.size() * sizeof(unsigned)),
                 triangleIndices.data(), GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(MeshVertex),
                          reinterpret_cast<const void *>(offsetof(MeshVertex, position)));
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(MeshVertex),
                          reinterpret_cast<const void *>(offsetof(MeshVertex, normal)));
    glEnableVertexAttribArray(2);
    glVertexAttribPointer(2, 4, GL_UNSIGNED_BYTE, GL_TRUE, sizeof(MeshVertex),
                          reinterpret_cast<const void *>(offsetof(MeshVertex, color)));
    glBindVertexArray(GLuint(previousVao));
    glBindBuffer(GL_ARRAY_BUFFER, 0);
}

ShadedMeshRenderer::~ShadedMeshRenderer()
{
    glDeleteVertexArrays(1, &vao);
    glDeleteBuffers(2, buffers);
}

void ShadedMeshRenderer::render(const float modelView[16], const float projection[16], const Lighting &lighting,
                                bool flat)
{
    ScopedGlState savedState;
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glUseProgram(program->id());
    glUniformMatrix4fv(program->uniform("projection"), 1, GL_FALSE, projection);
    setModelViewUniforms(*program, modelView);
    setLightingUniforms(*program, lighting);
    glUniform1i(program->uniform("flatShading"), flat ? 1 : 0);
    glBindVertexArray(vao);
    glDrawElements(GL_TRIANGLES, indexCount, GL_UNSIGNED_INT, nullptr);
}

} // namespace splat
