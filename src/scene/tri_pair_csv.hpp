#pragma once
// Reader for the triangle-pair CSV of `glcollide query tritri` (docs/narrow-phase.md):
// one pair per line, 18 decimal numbers a0 a1 a2 b0 b1 b2 (x, y, z each) separated by commas,
// spaces or tabs allowed around them; blank lines and lines whose first non-blank character is
// '#' are skipped. Values are rounded to float, the precision the GPU works in.

#include <array>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace glcollide {

/// One pair: a0 a1 a2 b0 b1 b2, xyz each (same layout as cpu::FloatTriPair and passes::TriTriPair).
using TriPairRow = std::array<float, 18>;

/// A data row and the line it came from (1-based).
struct TriPairCsv {
    std::vector<TriPairRow> pairs;
    std::vector<std::size_t> lines;
};

/// Parses CSV text. Throws Error "<fileName>:<line>: <what is wrong>" for a row with a field
/// count other than 18, a field that is not a decimal number, or one that is not finite or
/// outside float range (|v| > 3.4028235e38); values smaller than the smallest float round
/// to a denormal or zero, as the float conversion does.
TriPairCsv parseTriPairCsv(std::string_view text, const std::string& fileName);

/// Reads and parses a file; throws Error if it cannot be opened.
TriPairCsv readTriPairCsv(const std::filesystem::path& path);

} // namespace glcollide
