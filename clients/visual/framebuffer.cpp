#include "clients/visual/framebuffer.hpp"

#include <algorithm>
#include <cstdio>

#include "clients/visual/gl_error.hpp"

namespace thx::visual {
namespace {

GLuint renderbuffer(GLenum format, int width, int height) {
  GLuint rb = 0;
  glGenRenderbuffers(1, &rb);
  glBindRenderbuffer(GL_RENDERBUFFER, rb);
  glRenderbufferStorage(GL_RENDERBUFFER, format, width, height);
  return rb;
}

// GL's rows start at the bottom; images start at the top.
template <class T>
void flipRows(std::vector<T>& pixels, int width, int height) {
  const std::size_t row = std::size_t(width) * 4;
  for (int y = 0; y < height / 2; ++y)
    std::swap_ranges(pixels.begin() + std::ptrdiff_t(y * row), pixels.begin() + std::ptrdiff_t((y + 1) * row),
                     pixels.begin() + std::ptrdiff_t((height - 1 - y) * row));
}

}  // namespace

Framebuffer::Framebuffer(int width, int height, bool with_hit_buffer) : width_(width), height_(height) {
  glGenFramebuffers(1, &fbo_);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  colour_ = renderbuffer(GL_RGBA8, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour_);
  if (with_hit_buffer) {
    hit_ = renderbuffer(GL_RGBA32F, width, height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_RENDERBUFFER, hit_);
  }
  depth_ = renderbuffer(GL_DEPTH24_STENCIL8, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, depth_);
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    char code[16];
    std::snprintf(code, sizeof code, "0x%04x", unsigned(status));
    throw GlError(std::string("framebuffer ") + std::to_string(width) + "x" + std::to_string(height) +
                  " incomplete (status " + code + ")");
  }
  checkGl("Framebuffer()");
}

Framebuffer::~Framebuffer() {
  glDeleteFramebuffers(1, &fbo_);
  glDeleteRenderbuffers(1, &colour_);
  if (hit_) glDeleteRenderbuffers(1, &hit_);
  glDeleteRenderbuffers(1, &depth_);
}

void Framebuffer::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  const GLenum buffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glDrawBuffers(hit_ ? 2 : 1, buffers);
  glViewport(0, 0, width_, height_);
}

// One RGBA8 read of `buffer` in framebuffer `fbo` (0 = the window's), flipped to image order.
static Rgba8Image readRgba8(GLuint fbo, GLenum buffer, int width, int height, const char* where) {
  Rgba8Image image{width, height, std::vector<std::uint8_t>(std::size_t(width) * height * 4)};
  glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
  glReadBuffer(buffer);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, image.rgba.data());
  checkGl(where);
  flipRows(image.rgba, width, height);
  return image;
}

Rgba8Image Framebuffer::readColour() const {
  return readRgba8(fbo_, GL_COLOR_ATTACHMENT0, width_, height_, "Framebuffer::readColour");
}

Rgba8Image readWindowBackBuffer(int width, int height) {
  return readRgba8(0, GL_BACK, width, height, "readWindowBackBuffer");
}

FloatImage Framebuffer::readHits() const {
  FloatImage image{width_, height_, std::vector<float>(std::size_t(width_) * height_ * 4)};
  glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo_);
  glReadBuffer(GL_COLOR_ATTACHMENT1);
  glReadPixels(0, 0, width_, height_, GL_RGBA, GL_FLOAT, image.rgba.data());
  checkGl("Framebuffer::readHits");
  flipRows(image.rgba, width_, height_);
  return image;
}

}  // namespace thx::visual
