#pragma once
// The report's sections, one per modality, each built from the results files in one folder
// (docs/results/ by default). A missing file gives a section marked "not measured"; a malformed
// one throws thx::Error naming the file and the field.
#include <filesystem>

#include "base/error.hpp"
#include "tools/report/report_data.hpp"

namespace thx::bench::report {

Section hapticsSection(const std::filesystem::path& results);  // bench_force_error(_mesh).json
Section physicsSection(const std::filesystem::path& results);  // bench_physics.json
Section visualSection(const std::filesystem::path& results);   // bench_visual.json
Section femSection(const std::filesystem::path& results);      // bench_audio_fem.json
Section synthSection(const std::filesystem::path& results);    // bench_audio_synth.json

}  // namespace thx::bench::report
