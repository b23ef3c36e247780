#pragma once
// Perspective-correct elliptical splatting (paper section 4) with plain OpenGL 3.3 and GLSL 3.30,
// usable inside MeshLab (render_ellipsesplat) and outside it (tools/splat_render, tests).
//
// Every splat is drawn as an instanced screen-space quad bounding its projected ellipse; the
// fragment shader intersects the pixel's viewing ray with the ellipse plane (equation (1),
// [E F v]·(x, y, −t)ᵀ = −p), discards pixels outside the ellipse and writes the true depth.
// The three-pass pipeline: (1) visibility: depth only, every splat pushed back by ε along the
// viewing ray; (2) accumulation: Gaussian-weighted colours, normals and depths of all splats
// within ε of the visible surface, added into float render targets; (3) normalisation and
// lighting in a full-screen pass that also writes depth into the caller's framebuffer.
//
// All calls need the same current GL context (3.3 or newer, GLEW initialised) as the
// constructor; matrices are column-major 4x4 float arrays as OpenGL stores them.

#include "surfel_arrays.h"

#include <GL/glew.h>

#include <memory>
#include <string>
#include <vector>

namespace splat {

class GlProgram;

// Why this context cannot run the renderer, or an empty string when it can.
std::string unsupportedReason();

// The surfels of one point set in GPU memory (interleaved per-splat attributes).
class SplatCloud
{
public:
    explicit SplatCloud(const SurfelArrays &surfels, const std::uint8_t defaultColor[4]);
    ~SplatCloud();
    SplatCloud(const SplatCloud &) = delete;
    SplatCloud &operator=(const SplatCloud &) = delete;

    GLsizei size() const { return count; }
    GLuint vertexArray() const { return vao; }

private:
    GLuint buffer = 0;
    GLuint vao = 0;
    GLsizei count = 0;
};

struct Lighting
{
    float towardsLight[3] = {0.0f, 0.0f, 1.0f}; // eye space, need not be normalised (a headlight)
    float ambient[3] = {0.2f, 0.2f, 0.2f};
    float diffuse[3] = {0.8f, 0.8f, 0.8f};
    float specular[3] = {0.25f, 0.25f, 0.25f};
    float shininess = 32.0f;
};

enum class SplatMode
{
    ThreePass,     // ε-z-buffer visibility, Gaussian blending, deferred lighting (smooth)
    OnePassOpaque, // nearest splat wins, lit with its own normal (shows the splat structure)
    Points,        // fixed-size GL points, lit per point (MeshLab's usual point drawing)
};

struct SplatSettings
{
    SplatMode mode = SplatMode::ThreePass;
    float splatScale = 1.0f;        // multiplies both semi-axes of every ellipse
    float depthOffsetFactor = 1.0f; // ε of each splat, in units of its (scaled) major semi-axis
    bool visibilityPass = true;     // three-pass only; off = blend every splat (for comparisons)
    bool cullBackFaces = true;      // skip splats whose normal faces away from the viewer
    float pointSize = 3.0f;         // pixels, Points mode
};

struct Viewport
{
    int x = 0, y = 0, width = 0, height = 0;
};

struct SplatDrawItem
{
    const SplatCloud *cloud;
    float modelView[16];
};

class EllipseSplatRenderer
{
public:
    // Compiles the shaders; throws std::runtime_error when they do not build on this context.
    EllipseSplatRenderer();
    ~EllipseSplatRenderer();
    EllipseSplatRenderer(const EllipseSplatRenderer &) = delete;
    EllipseSplatRenderer &operator=(const EllipseSplatRenderer &) = delete;

    // Draws the clouds into the framebuffer bound at the call, inside `viewport`, depth-tested
    // against and writing into its depth buffer. The GL state it changes is restored.
    void render(const std::vector<SplatDrawItem> &items, const float projection[16], const Viewport &viewport,
                const Lighting &lighting, const SplatSettings &settings);

private:
    struct AccumulationTargets;

    void drawSplats(const GlProgram &program, const std::vector<SplatDrawItem> &items, const float projection[16],
                    const Viewport &viewport, const Lighting &lighting, const SplatSettings &settings);
    void drawPoints(const std::vector<SplatDrawItem> &items, const float projection[16], const Lighting &lighting,
                    const SplatSettings &settings);
    void renderThreePasses(const std::vector<SplatDrawItem> &items, const float projection[16],
                           const Viewport &viewport, const Lighting &lighting, const SplatSettings &settings,
                           GLuint callerFramebuffer);

    std::unique_ptr<GlProgram> visibilityProgram;
    std::unique_ptr<GlProgram> accumulationProgram;
    std::unique_ptr<GlProgram> normalizationProgram;
    std::unique_ptr<GlProgram> opaqueProgram;
    std::unique_ptr<GlProgram> pointProgram;
    std::unique_ptr<AccumulationTargets> targets;
    GLuint screenTriangleBuffer = 0;
    GLuint screenTriangleVao = 0;
};

// Triangles lit exactly like the splats (same camera, light and material), as a reference
// image for the splatting: flat (per-face normal) or Phong (interpolated vertex normals).
class ShadedMeshRenderer
{
public:
    // normals: per-vertex, only needed for Phong shading; colors: per-vertex rgba or empty.
    ShadedMeshRenderer(const std::vector<float> &positions, const std::vector<float> &normals,
                       const std::vector<std::uint8_t> &colors, const std::vector<unsigned> &triangleIndices,
                       const std::uint8_t defaultColor[4]);
    ~ShadedMeshRenderer();
    ShadedMeshRenderer(const ShadedMeshRenderer &) = delete;
    ShadedMeshRenderer &operator=(const ShadedMeshRenderer &) = delete;

    void render(const float modelView[16], const float projection[16], const Lighting &lighting, bool flat);

private:
    std::unique_ptr<GlProgram> program;
    GLuint buffers[2] = {0, 0};
    GLuint vao = 0;
    GLsizei indexCount = 0;
};

} // namespace splat
