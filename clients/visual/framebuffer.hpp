#pragma once
// The one render target: an offscreen framebuffer with an 8-bit RGBA colour (what is shown and
// saved), optionally a float RGBA attachment the surface shader fills with its hit point (u, v,
// depth) for the reference tests, and a 24-bit depth buffer. Both presenters read from it.
#include <cstdint>
#include <vector>

#include "clients/visual/gl_api.hpp"

namespace thx::visual {

// Top row first (image order), as files and the CPU references expect.
struct Rgba8Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;
  std::uint8_t at(int x, int y, int c) const { return rgba[(std::size_t(y) * width + x) * 4 + c]; }
};
struct FloatImage {
  int width = 0, height = 0;
  std::vector<float> rgba;
  float at(int x, int y, int c) const { return rgba[(std::size_t(y) * width + x) * 4 + c]; }
};

class Framebuffer {
 public:
  // Throws GlError when the driver reports the framebuffer incomplete.
  Framebuffer(int width, int height, bool with_hit_buffer);
  ~Framebuffer();
  Framebuffer(const Framebuffer&) = delete;
  Framebuffer& operator=(const Framebuffer&) = delete;

  void bind() const;
  int width() const { return width_; }
  int height() const { return height_; }
  bool hasHitBuffer() const { return hit_ != 0; }
  Rgba8Image readColour() const;
  FloatImage readHits() const;  // requires hasHitBuffer()

 private:
  int width_, height_;
  GLuint fbo_ = 0, colour_ = 0, hit_ = 0, depth_ = 0;
};

// The window's back buffer (the default framebuffer), top row first: what the window presenter
// is about to show.
Rgba8Image readWindowBackBuffer(int width, int height);

}  // namespace thx::visual
