#pragma once
// A hidden OpenGL context (Qt offscreen surface; needs a QGuiApplication and, on Linux, an X
// display such as Xvfb) and a framebuffer object to render images into and read them back.

#include <QImage>

#include <memory>
#include <vector>

class QOffscreenSurface;
class QOpenGLContext;

namespace splat {

using GlName = unsigned int; // GLuint, without including GL headers here (see offscreen_context.cpp)

class OffscreenGl
{
public:
    // Creates a compatibility-profile context (3.3 or newer), makes it current and initialises
    // GLEW; throws std::runtime_error when any step fails.
    OffscreenGl();
    ~OffscreenGl();

private:
    static void initialiseGlew(); // in offscreen_gl.cpp, which includes GLEW

    std::unique_ptr<QOffscreenSurface> surface;
    std::unique_ptr<QOpenGLContext> context;
};

// RGBA8 colour + 32-bit float depth, bound for drawing while it is alive.
class RenderTarget
{
public:
    RenderTarget(int width, int height);
    ~RenderTarget();
    RenderTarget(const RenderTarget &) = delete;
    RenderTarget &operator=(const RenderTarget &) = delete;

    void clear(const float rgba[4]);
    QImage readColor() const;              // top row first, as images are stored
    std::vector<float> readDepth() const;  // window depth in [0, 1], bottom row first like GL
    int width() const { return w; }
    int height() const { return h; }

private:
    int w, h;
    GlName framebuffer = 0, renderbuffers[2] = {0, 0};
};

} // namespace splat
