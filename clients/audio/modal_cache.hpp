#pragma once
// The modal cache: one binary file per (mesh, material, solver settings), named by a 64-bit
// FNV-1a key over all three. Layout in docs/audio.md §2.
#include <cstdint>
#include <optional>
#include <string>

#include "clients/audio/elastic_material.hpp"
#include "clients/audio/modal_analysis.hpp"
#include "clients/audio/tet_mesh.hpp"

namespace thx::audio {

inline constexpr std::uint32_t kModalCacheVersion = 1;

std::uint64_t modalCacheKey(const TetMesh& mesh, const ElasticMaterial& material, const ModalSettings& settings);
std::string modalCachePath(const std::string& dir, std::uint64_t key);

// The cached solution, or nothing if the file is absent, of another key, or damaged (a damaged
// file is reported through `warn` and then ignored).
std::optional<ModalSolution> readModalCache(const std::string& path, std::uint64_t key,
                                            const std::function<void(const std::string&)>& warn = {});
// Writes atomically (temporary file, then rename). Throws thx::Error (Io) if it cannot.
void writeModalCache(const std::string& path, std::uint64_t key, const ModalSolution& solution);

}  // namespace thx::audio
