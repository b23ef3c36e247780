#include "offscreen_gl.h"

#include <GL/glew.h>

#include <stdexcept>
#include <string>

namespace splat {

void OffscreenGl::initialiseGlew()
{
    glewExperimental = GL_TRUE; // also load entry points a core context does not advertise
    const GLenum status = glewInit();
    if (status != GLEW_OK)
        throw std::runtime_error(std::string("GLEW initialisation failed: ") +
                                 reinterpret_cast<const char *>(glewGetErrorString(status)));
    glGetError(); // glewInit may leave GL_INVALID_ENUM behind
}

RenderTarget::RenderTarget(int width, int height) : w(width), h(height)
{
    glGenFramebuffers(1, &framebuffer);
    glGenRenderbuffers(2, renderbuffers);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glBindRenderbuffer(GL_RENDERBUFFER, renderbuffers[0]);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, w, h);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, renderbuffers[0]);
    glBindRenderbuffer(GL_RENDERBUFFER, renderbuffers[1]);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, w, h);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, renderbuffers[1]);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw std::runtime_error("offscreen framebuffer incomplete");
    glViewport(0, 0, w, h);
}

RenderTarget::~RenderTarget()
{
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &framebuffer);
    glDeleteRenderbuffers(2, renderbuffers);
}

void RenderTarget::clear(const float rgba[4])
{
    const float farthest = 1.0f;
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glViewport(0, 0, w, h);
    glDepthMask(GL_TRUE);
    glClearBufferfv(GL_COLOR, 0, rgba);
    glClearBufferfv(GL_DEPTH, 0, &farthest);
}

QImage RenderTarget::readColor() const
{
    QImage image(w, h, QImage::Format_RGBA8888);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, image.bits());
    return image.mirrored(); // GL's first row is the bottom one
}

std::vector<float> RenderTarget::readDepth() const
{
    std::vector<float> depth(std::size_t(w) * std::size_t(h));
    glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, w, h, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
    return depth;
}

} // namespace splat
