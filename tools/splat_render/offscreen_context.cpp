// The Qt side of OffscreenGl, kept apart from GLEW: Qt's OpenGL headers and glew.h do not mix.
#include "offscreen_gl.h"

#include <QOffscreenSurface>
#include <QOpenGLContext>

#include <stdexcept>

namespace splat {

OffscreenGl::OffscreenGl() : surface(new QOffscreenSurface), context(new QOpenGLContext)
{
    QSurfaceFormat format;
    format.setVersion(3, 3);
    format.setProfile(QSurfaceFormat::CompatibilityProfile); // like MeshLab's own context
    context->setFormat(format);
    if (!context->create())
        throw std::runtime_error("cannot create an OpenGL 3.3 context (is DISPLAY set? run under xvfb-run)");
    surface->setFormat(context->format());
    surface->create();
    if (!context->makeCurrent(surface.get()))
        throw std::runtime_error("cannot make the OpenGL context current");
    initialiseGlew();
}

OffscreenGl::~OffscreenGl()
{
    context->doneCurrent();
}

} // namespace splat
