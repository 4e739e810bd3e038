#pragma once
// Reader for CCD query CSV files, the layout of the CCD benchmark (Wang et al. 2021,
// "Sample-Queries"; Scalable-CCD's query files): 8 rows per query, one point per row, rows 1-4
// the four points at t = 0 and rows 5-8 the same points at t = 1 (vertex-face: the vertex, then
// the triangle's corners; edge-edge: edge A's ends, then edge B's). A row is x,y,z as either
//   - 6 integers: numerator,denominator of x, then of y, then of z (any size; denominator > 0), or
//   - 3 decimal numbers ("-0.25", "1.25e-3", "7"), read as the exact rationals they denote,
// optionally followed by a 7th (4th) field, the ground truth 0 or 1, equal on the 8 rows of a
// query. Fields are separated by commas, with spaces or tabs allowed around them; blank lines and
// lines whose first non-blank character is '#' are skipped. Every value must round to a finite
// float (|x| < 2^128 - 2^103), the precision the GPU computes in (docs/ccd.md, "query ccd").
//
// Here and not in scene/: the values are GMP rationals, and the scene module links no GMP.

#include "cpu/oracle/exact_ccd.hpp"

#include <gmpxx.h>

#include <array>
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace glcollide::cpu {

/// One query as read: the exact points, the ground truth when the file has that column, and the
/// line of each of its 8 rows (1-based).
struct CcdCsvQuery {
    RationalCcdQuery points;
    std::optional<bool> truth;
    std::array<std::size_t, 8> lines{};
};

/// Parses CSV text. Throws Error "<fileName>:<line>: <what is wrong>" for a row with a field count
/// other than 3, 4, 6 or 7, a field that is not an integer (6 or 7 fields) or a decimal number
/// (3 or 4 fields), a denominator that is not positive, a value that does not round to a finite
/// float, a ground truth other than 0 or 1 or one that differs within a query (or is given on some
/// of its rows only), and a file that ends inside a query (the line of that query's first row).
std::vector<CcdCsvQuery> parseCcdQueryCsv(std::string_view text, const std::string& fileName);

/// Reads and parses a file; throws Error if it cannot be opened.
std::vector<CcdCsvQuery> readCcdQueryCsv(const std::filesystem::path& path);

/// The exact rational a decimal number denotes: [+-]digits[.digits][(e|E)[+-]digits] (at least one
/// digit before or after the point; decimal exponent within +-100000). Nothing else: no spaces,
/// no "inf" or "nan", no hexadecimal. std::nullopt when `text` is not such a number.
std::optional<mpq_class> parseExactDecimal(std::string_view text);

} // namespace glcollide::cpu
