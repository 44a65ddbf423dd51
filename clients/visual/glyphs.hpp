#pragma once
// The letters on letter blocks: a 5x7 bitmap font (A-Z, 0-9; lower case as upper case), drawn by
// the object shader on a block's two largest-normal (±z) faces. A box whose scene name is one
// letter or digit is a letter block (scenes/letter_blocks.yaml: blocks A, B, C).
#include <array>
#include <cstdint>
#include <optional>
#include <string>

namespace thx::visual {

// Rows top to bottom; bit 4 is the leftmost column. nullopt for characters without a glyph.
using Glyph = std::array<std::uint8_t, 7>;
std::optional<Glyph> glyph5x7(char c);

// The letter a scene object's name gives it (one letter or digit), else 0.
char blockLetter(const std::string& object_name);

}  // namespace thx::visual
