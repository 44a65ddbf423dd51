#include "clients/audio/modal_cache.hpp"

#include "base/error.hpp"

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

namespace thx::audio {
namespace {

constexpr char kMagic[8] = {'T', 'H', 'X', 'M', 'O', 'D', 'E', 'S'};

class Fnv1a {
 public:
  void bytes(const void* p, std::size_t n) {
    const auto* b = static_cast<const unsigned char*>(p);
    for (std::size_t i = 0; i < n; ++i) h_ = (h_ ^ b[i]) * 1099511628211ull;
  }
  template <class T>
  void value(const T& v) {
    bytes(&v, sizeof v);
  }
  std::uint64_t digest() const { return h_; }

 private:
  std::uint64_t h_ = 14695981039346656037ull;
};

struct Header {
  char magic[8];
  std::uint32_t version;
  std::uint32_t rigid_modes;
  std::uint64_t key;
  std::uint32_t mesh_dofs, free_dofs, modes, reserved;
};

}  // namespace

std::uint64_t modalCacheKey(const TetMesh& mesh, const ElasticMaterial& material, const ModalSettings& settings) {
  Fnv1a h;
  h.bytes(kMagic, sizeof kMagic);
  h.value(kModalCacheVersion);
  h.value(int(mesh.order));
  h.value(std::uint64_t(mesh.nodes.size()));
  for (const Eigen::Vector3d& x : mesh.nodes) h.bytes(x.data(), 3 * sizeof(double));
  h.value(std::uint64_t(mesh.tets.size()));
  for (const auto& t : mesh.tets) h.bytes(t.data(), sizeof(int) * std::size_t(mesh.nodesPerTet()));
  for (std::size_t i = 0; i < mesh.nodes.size(); ++i) h.value(char(i < mesh.clamped.size() && mesh.clamped[i]));
  // The solve depends on density, stiffness and Poisson ratio; damping is applied afterwards.
  h.value(material.density_kg_per_m3);
  h.value(material.youngs_modulus_pa);
  h.value(material.poisson_ratio);
  h.value(settings.elastic_modes);
  h.value(settings.shift_hz);
  h.value(settings.tolerance);
  h.value(settings.max_iterations);
  h.value(settings.lanczos_vectors);
  h.value(settings.rigid_below_hz);
  h.value(int(settings.factorization));
  return h.digest();
}

std::string modalCachePath(const std::string& dir, std::uint64_t key) {
  char name[32];
  std::snprintf(name, sizeof name, "%016llx.modes", static_cast<unsigned long long>(key));
  return (std::filesystem::path(dir) / name).string();
}

std::optional<ModalSolution> readModalCache(const std::string& path, std::uint64_t key,
                                            const std::function<void(const std::string&)>& warn) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  auto damaged = [&](const std::string& why) -> std::optional<ModalSolution> {
    if (warn) warn("modal cache " + path + ": " + why + "; solving again");
    return std::nullopt;
  };
  Header hd{};
  if (!in.read(reinterpret_cast<char*>(&hd), sizeof hd)) return damaged("shorter than its header");
  if (std::memcmp(hd.magic, kMagic, sizeof kMagic) != 0) return damaged("not a modal cache file");
  if (hd.version != kModalCacheVersion) return damaged("format version " + std::to_string(hd.version));
  if (hd.key != key) return damaged("another key");
  ModalSolution s;
  s.mesh_dofs = int(hd.mesh_dofs), s.free_dofs = int(hd.free_dofs), s.rigid_modes = int(hd.rigid_modes);
  s.rigid_hz.resize(hd.rigid_modes);
  s.omega_rad_per_s.resize(hd.modes);
  s.shapes.resize(hd.mesh_dofs, hd.modes);
  Fnv1a h;
  h.value(hd);
  auto block = [&](double* p, std::size_t count) {
    if (!in.read(reinterpret_cast<char*>(p), std::streamsize(count * sizeof(double)))) return false;
    h.bytes(p, count * sizeof(double));
    return true;
  };
  std::uint64_t checksum = 0;
  if (!block(s.rigid_hz.data(), hd.rigid_modes) || !block(s.omega_rad_per_s.data(), hd.modes) ||
      !block(s.shapes.data(), std::size_t(hd.mesh_dofs) * hd.modes) ||
      !in.read(reinterpret_cast<char*>(&checksum), sizeof checksum))
    return damaged("truncated");
  if (checksum != h.digest()) return damaged("checksum mismatch");
  s.from_cache = true;
  s.cache_file = path;
  return s;
}

void writeModalCache(const std::string& path, std::uint64_t key, const ModalSolution& s) {
  std::error_code ec;
  std::filesystem::create_directories(std::filesystem::path(path).parent_path(), ec);
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw Error(Error::Kind::Io, "modal cache " + tmp + ": cannot be written");
    Header hd{};
    std::memcpy(hd.magic, kMagic, sizeof kMagic);
    hd.version = kModalCacheVersion;
    hd.rigid_modes = std::uint32_t(s.rigid_modes);
    hd.key = key;
    hd.mesh_dofs = std::uint32_t(s.mesh_dofs), hd.free_dofs = std::uint32_t(s.free_dofs);
    hd.modes = std::uint32_t(s.omega_rad_per_s.size());
    Fnv1a h;
    h.value(hd);
    out.write(reinterpret_cast<const char*>(&hd), sizeof hd);
    auto block = [&](const double* p, std::size_t count) {
      out.write(reinterpret_cast<const char*>(p), std::streamsize(count * sizeof(double)));
      h.bytes(p, count * sizeof(double));
    };
    block(s.rigid_hz.data(), std::size_t(s.rigid_hz.size()));
    block(s.omega_rad_per_s.data(), std::size_t(s.omega_rad_per_s.size()));
    block(s.shapes.data(), std::size_t(s.shapes.size()));
    const std::uint64_t checksum = h.digest();
    out.write(reinterpret_cast<const char*>(&checksum), sizeof checksum);
    if (!out) throw Error(Error::Kind::Io, "modal cache " + tmp + ": write failed");
  }
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw Error(Error::Kind::Io, "modal cache " + path + ": cannot be renamed into place: " + ec.message());
}

}  // namespace thx::audio
