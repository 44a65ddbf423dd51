#include "clients/physics_client/pose_csv.hpp"

#include <stdexcept>

namespace thx::physclient {

PoseCsvSink::PoseCsvSink(const std::string& path) : path_(path), out_(std::fopen(path.c_str(), "w")) {
  if (out_ == nullptr) throw thx::Error(thx::Error::Kind::Io, path + ": cannot write the poses");
  std::fputs("t_s, object, x_m, y_m, z_m, x_local_m, y_local_m, h_local_m, speed_m_per_s, spin_rad_per_s\n", out_);
}

PoseCsvSink::~PoseCsvSink() {
  if (out_ != nullptr) std::fclose(out_);
}

void PoseCsvSink::poses(const PhysicsScene& scene, std::int64_t, const Eigen::Vector3d&) {
  for (const BodyState& b : scene.bodies()) {
    const scene::SceneObject& o = scene.scene().objects[std::size_t(b.id)];
    if (o.fixed) continue;  // obstacles never move
    const Eigen::Vector3d l = scene.surface().toLocal(b.p_world);
    std::fprintf(out_, "%.4f, %s, %.6f, %.6f, %.6f, %.6f, %.6f, %.6f, %.5f, %.4f\n", scene.simTime(), o.name.c_str(),
                 b.p_world.x(), b.p_world.y(), b.p_world.z(), l.x(), l.y(), l.z(), b.v_world.norm(), b.w_world.norm());
  }
  if (std::ferror(out_)) throw thx::Error(thx::Error::Kind::Io, path_ + ": write failed");
}

}  // namespace thx::physclient
