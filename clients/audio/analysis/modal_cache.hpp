#pragma once
// The modal cache: one binary file per (mesh, material, solver settings), named by a 64-bit
// FNV-1a key over all three. Layout in docs/audio.md §2.
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>
#include <string>

#include "clients/audio/analysis/elastic_material.hpp"
#include "clients/audio/analysis/modal_analysis.hpp"
#include "clients/audio/analysis/tet_mesh.hpp"

namespace thx::audio {

inline constexpr std::uint32_t kModalCacheVersion = 1;

std::uint64_t modalCacheKey(const TetMesh& mesh, const ElasticMaterial& material, const ModalSettings& settings);
std::string modalCachePath(const std::string& dir, std::uint64_t key);
// The cache folder every program uses unless told otherwise: $XDG_CACHE_HOME/texhaptics/modal,
// else $HOME/.cache/texhaptics/modal, else .texhaptics-cache/modal.
std::string defaultModalCacheDir();

// The cached solution, or nothing if the file is absent, of another key, or damaged (a damaged
// file is reported through `warn` and then ignored).
std::optional<ModalSolution> readModalCache(const std::string& path, std::uint64_t key,
                                            const std::function<void(const std::string&)>& warn = {});
// The same from the file's bytes (`source` names them in warnings). Refused before any allocation:
// counts that do not account for the size exactly, or beyond int; after the checksum: a nonzero
// reserved field, free DOFs above mesh DOFs, a value that is not finite, frequencies not ascending.
std::optional<ModalSolution> decodeModalCache(std::span<const std::uint8_t> bytes, std::uint64_t key,
                                              const std::string& source,
                                              const std::function<void(const std::string&)>& warn = {});
// The file's bytes for a solution (R from rigid_hz, D from the shapes' rows).
std::vector<std::uint8_t> encodeModalCache(std::uint64_t key, const ModalSolution& solution);
// Writes atomically (temporary file, then rename). Throws thx::Error (Io) if it cannot.
void writeModalCache(const std::string& path, std::uint64_t key, const ModalSolution& solution);

}  // namespace thx::audio
