#include "clients/visual/texture_upload.hpp"

#include <vector>

#include "clients/visual/gl_error.hpp"

namespace thx::visual {

SurfaceTexture::SurfaceTexture(const tex::TextureMap& map) {
  std::vector<float> texels(std::size_t(map.width()) * map.height() * 4);
  for (int j = 0; j < map.height(); ++j)
    for (int i = 0; i < map.width(); ++i) {
      const Eigen::Vector3f n = map.normal(i, j);
      float* t = &texels[(std::size_t(j) * map.width() + i) * 4];
      t[0] = n.x(), t[1] = n.y(), t[2] = n.z(), t[3] = map.depth(i, j);
    }
  glGenTextures(1, &texture_);
  glBindTexture(GL_TEXTURE_2D, texture_);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, map.width(), map.height(), 0, GL_RGBA, GL_FLOAT, texels.data());
  // Read only with texelFetch; the filters matter only for completeness.
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
  checkGl("SurfaceTexture()");
}

SurfaceTexture::~SurfaceTexture() { glDeleteTextures(1, &texture_); }

void SurfaceTexture::bind(GLenum unit) const {
  glActiveTexture(unit);
  glBindTexture(GL_TEXTURE_2D, texture_);
}

}  // namespace thx::visual
