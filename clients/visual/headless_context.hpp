#pragma once
// A headless OpenGL 3.3+ core context: EGL on Mesa's surfaceless platform, no window and no
// display server (on a machine without a GPU that is llvmpipe). Rendering goes into a Framebuffer.
#include <string>

namespace thx::visual {

class HeadlessContext {
 public:
  // Creates and makes current a core context (4.5 if available, else 3.3). Throws GlError naming
  // the failing EGL call, its error code and the packages that provide EGL and the Mesa driver.
  HeadlessContext();
  ~HeadlessContext();
  HeadlessContext(const HeadlessContext&) = delete;
  HeadlessContext& operator=(const HeadlessContext&) = delete;

  // "llvmpipe (LLVM 15.0.6, 256 bits), 4.5 (Core Profile) Mesa 22.3.6"
  std::string description() const;

 private:
  void* display_ = nullptr;  // EGLDisplay
  void* context_ = nullptr;  // EGLContext
};

}  // namespace thx::visual
