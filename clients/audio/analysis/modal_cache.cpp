#include "clients/audio/analysis/modal_cache.hpp"

#include "base/error.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
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

std::string defaultModalCacheDir() {
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return std::string(x) + "/texhaptics/modal";
  if (const char* h = std::getenv("HOME"); h && *h) return std::string(h) + "/.cache/texhaptics/modal";
  return ".texhaptics-cache/modal";
}

std::optional<ModalSolution> decodeModalCache(std::span<const std::uint8_t> bytes, std::uint64_t key,
                                              const std::string& source,
                                              const std::function<void(const std::string&)>& warn) {
  auto damaged = [&](const std::string& why) -> std::optional<ModalSolution> {
    if (warn) warn("modal cache " + source + ": " + why + "; solving again");
    return std::nullopt;
  };
  Header hd{};
  if (bytes.size() < sizeof hd + sizeof(std::uint64_t)) return damaged("shorter than its header");
  std::memcpy(&hd, bytes.data(), sizeof hd);
  if (std::memcmp(hd.magic, kMagic, sizeof kMagic) != 0) return damaged("not a modal cache file");
  if (hd.version != kModalCacheVersion) return damaged("format version " + std::to_string(hd.version));
  if (hd.key != key) return damaged("another key");
  if (hd.reserved != 0) return damaged("reserved header field " + std::to_string(hd.reserved) + ", expected 0");
  constexpr std::uint32_t kMaxCount = std::numeric_limits<int>::max();
  if (hd.rigid_modes > kMaxCount || hd.mesh_dofs > kMaxCount || hd.modes > kMaxCount)
    return damaged("counts R " + std::to_string(hd.rigid_modes) + ", D " + std::to_string(hd.mesh_dofs) + ", N " +
                   std::to_string(hd.modes) + " beyond " + std::to_string(kMaxCount));
  if (hd.free_dofs > hd.mesh_dofs)
    return damaged("free DOFs " + std::to_string(hd.free_dofs) + " above mesh DOFs " + std::to_string(hd.mesh_dofs));
  // The counts must account for the file's size exactly before anything is allocated from them.
  const std::uint64_t doubles = std::uint64_t(hd.rigid_modes) + hd.modes + std::uint64_t(hd.mesh_dofs) * hd.modes;
  const std::uint64_t available = (bytes.size() - sizeof hd - sizeof(std::uint64_t)) / sizeof(double);
  if (doubles != available || (bytes.size() - sizeof hd) % sizeof(double) != 0)
    return damaged(std::to_string(bytes.size()) + " bytes where R " + std::to_string(hd.rigid_modes) + ", D " +
                   std::to_string(hd.mesh_dofs) + ", N " + std::to_string(hd.modes) + " need " +
                   std::to_string(sizeof hd + 8 * (doubles + 1)) + " (truncated or trailing data)");
  std::uint64_t checksum = 0;
  std::memcpy(&checksum, bytes.data() + bytes.size() - sizeof checksum, sizeof checksum);
  Fnv1a h;
  h.bytes(bytes.data(), bytes.size() - sizeof checksum);
  if (checksum != h.digest()) return damaged("checksum mismatch");

  ModalSolution s;
  s.mesh_dofs = int(hd.mesh_dofs), s.free_dofs = int(hd.free_dofs), s.rigid_modes = int(hd.rigid_modes);
  s.rigid_hz.resize(hd.rigid_modes);
  s.omega_rad_per_s.resize(hd.modes);
  s.shapes.resize(hd.mesh_dofs, hd.modes);
  std::size_t at = sizeof hd;
  auto block = [&](double* p, std::size_t count) {
    if (count == 0) return true;  // an empty Eigen vector's data() is null, not for memcpy
    std::memcpy(p, bytes.data() + at, count * sizeof(double));
    at += count * sizeof(double);
    return std::all_of(p, p + count, [](double v) { return std::isfinite(v); });
  };
  if (!block(s.rigid_hz.data(), hd.rigid_modes)) return damaged("a rigid-mode frequency is not finite");
  if (!block(s.omega_rad_per_s.data(), hd.modes)) return damaged("an elastic frequency is not finite");
  for (Eigen::Index m = 0; m < s.omega_rad_per_s.size(); ++m)
    if (s.omega_rad_per_s[m] < 0.0 || (m > 0 && s.omega_rad_per_s[m] < s.omega_rad_per_s[m - 1]))
      return damaged("elastic frequencies not ascending from 0 at mode " + std::to_string(m));
  if (!block(s.shapes.data(), std::size_t(hd.mesh_dofs) * hd.modes)) return damaged("a mode shape is not finite");
  s.from_cache = true;
  s.cache_file = source;
  return s;
}

std::optional<ModalSolution> readModalCache(const std::string& path, std::uint64_t key,
                                            const std::function<void(const std::string&)>& warn) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  const std::vector<std::uint8_t> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  return decodeModalCache(bytes, key, path, warn);
}

std::vector<std::uint8_t> encodeModalCache(std::uint64_t key, const ModalSolution& s) {
  Header hd{};
  std::memcpy(hd.magic, kMagic, sizeof kMagic);
  hd.version = kModalCacheVersion;
  hd.rigid_modes = std::uint32_t(s.rigid_hz.size());
  hd.key = key;
  hd.mesh_dofs = std::uint32_t(s.shapes.rows()), hd.free_dofs = std::uint32_t(s.free_dofs);
  hd.modes = std::uint32_t(s.omega_rad_per_s.size());
  std::vector<std::uint8_t> out(sizeof hd);
  std::memcpy(out.data(), &hd, sizeof hd);
  auto block = [&](const double* p, std::size_t count) {
    const auto* b = reinterpret_cast<const std::uint8_t*>(p);
    out.insert(out.end(), b, b + count * sizeof(double));
  };
  block(s.rigid_hz.data(), std::size_t(s.rigid_hz.size()));
  block(s.omega_rad_per_s.data(), std::size_t(s.omega_rad_per_s.size()));
  block(s.shapes.data(), std::size_t(s.shapes.size()));
  Fnv1a h;
  h.bytes(out.data(), out.size());
  const std::uint64_t checksum = h.digest();
  const auto* c = reinterpret_cast<const std::uint8_t*>(&checksum);
  out.insert(out.end(), c, c + sizeof checksum);
  return out;
}

void writeModalCache(const std::string& path, std::uint64_t key, const ModalSolution& s) {
  std::error_code ec;
  std::filesystem::create_directories(std::filesystem::path(path).parent_path(), ec);
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw Error(Error::Kind::Io, "modal cache " + tmp + ": cannot be written");
    const std::vector<std::uint8_t> bytes = encodeModalCache(key, s);
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    if (!out) throw Error(Error::Kind::Io, "modal cache " + tmp + ": write failed");
  }
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw Error(Error::Kind::Io, "modal cache " + path + ": cannot be renamed into place: " + ec.message());
}

}  // namespace thx::audio
