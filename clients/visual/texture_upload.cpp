#include "clients/visual/texture_upload.hpp"

#include <vector>

#include "clients/visual/gl_error.hpp"

namespace thx::visual {

SurfaceTexture::SurfaceTexture(const tex::TextureMap& map, const tex::SampleOptions& sampling) {
  std::vector<float> texels(std::size_t(map.width()) * map.height() * 4);
  std::vector<float> depths(std::size_t(map.width()) * map.height());
  for (int j = 0; j < map.height(); ++j)
    for (int i = 0; i < map.width(); ++i) {
      const Eigen::Vector3f n = map.normal(i, j);
      float* t = &texels[(std::size_t(j) * map.width() + i) * 4];
      t[0] = n.x(), t[1] = n.y(), t[2] = n.z(), t[3] = map.depth(i, j);
      depths[std::size_t(j) * map.width() + i] = t[3];
    }
  glGenTextures(1, &texture_);
  glBindTexture(GL_TEXTURE_2D, texture_);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, map.width(), map.height(), 0, GL_RGBA, GL_FLOAT, texels.data());
  // Read only with texelFetch; the filters matter only for completeness.
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);

  glGenTextures(1, &depths_);
  glBindTexture(GL_TEXTURE_2D, depths_);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, map.width(), map.height(), 0, GL_RED, GL_FLOAT, depths.data());
  const GLint filter = sampling.filter == tex::Filter::Bilinear ? GL_LINEAR : GL_NEAREST;
  const GLint wrap = sampling.address == tex::Address::Wrap ? GL_REPEAT : GL_CLAMP_TO_EDGE;
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, wrap);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, wrap);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
  checkGl("SurfaceTexture()");
}

SurfaceTexture::~SurfaceTexture() {
  glDeleteTextures(1, &texture_);
  glDeleteTextures(1, &depths_);
}

void SurfaceTexture::bind(GLenum texels_unit, GLenum depths_unit) const {
  glActiveTexture(texels_unit);
  glBindTexture(GL_TEXTURE_2D, texture_);
  glActiveTexture(depths_unit);
  glBindTexture(GL_TEXTURE_2D, depths_);
}

MaxMipmapTexture::MaxMipmapTexture(const MaxMipmap& mipmap) {
  glGenTextures(1, &texture_);
  glBindTexture(GL_TEXTURE_2D, texture_);
  for (int level = 0; level <= mipmap.topLevel(); ++level) {
    const MaxMipmapLevel& l = mipmap.levels[std::size_t(level)];
    glTexImage2D(GL_TEXTURE_2D, level, GL_RGBA32F, l.width, l.height, 0, GL_RGBA, GL_FLOAT, l.depths.data());
  }
  // Read only with texelFetch; the parameters make the chain complete.
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_BASE_LEVEL, 0);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, mipmap.topLevel());
  checkGl("MaxMipmapTexture()");
}

MaxMipmapTexture::~MaxMipmapTexture() { glDeleteTextures(1, &texture_); }

void MaxMipmapTexture::bind(GLenum unit) const {
  glActiveTexture(unit);
  glBindTexture(GL_TEXTURE_2D, texture_);
}

}  // namespace thx::visual
