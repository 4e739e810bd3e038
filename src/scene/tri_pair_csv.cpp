#include "scene/tri_pair_csv.hpp"

#include <glcollide/error.hpp>

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <system_error>

namespace glcollide {
namespace {

std::string_view trim(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
    return s;
}

const double kFloatOverflow = std::ldexp(1.0, 128) - std::ldexp(1.0, 103);

std::string where(const std::string& file, std::size_t line) {
    return file + ":" + std::to_string(line) + ": ";
}

} // namespace

TriPairCsv parseTriPairCsv(std::string_view text, const std::string& fileName) {
    TriPairCsv out;
    std::size_t lineNo = 0, pos = 0;
    while (pos < text.size()) {
        std::size_t end = text.find('\n', pos);
        if (end == std::string_view::npos) end = text.size();
        const std::string_view line = trim(text.substr(pos, end - pos));
        pos = end + 1;
        ++lineNo;
        if (line.empty() || line.front() == '#') continue;

        std::vector<std::string_view> fields;
        for (std::size_t start = 0;;) {
            const std::size_t comma = line.find(',', start);
            fields.push_back(trim(line.substr(start, comma == std::string_view::npos ? std::string_view::npos
                                                                                     : comma - start)));
            if (comma == std::string_view::npos) break;
            start = comma + 1;
        }
        if (fields.size() != 18)
            throw Error(where(fileName, lineNo) +
                        "expected 18 numbers separated by commas (a0 a1 a2 b0 b1 b2, x y z each), got " +
                        std::to_string(fields.size()) + " field" + (fields.size() == 1 ? "" : "s"));
        TriPairRow row{};
        for (std::size_t k = 0; k < 18; ++k) {
            std::string_view f = fields[k];
            const std::string label = "field " + std::to_string(k + 1) + " '" + std::string(f) + "'";
            if (!f.empty() && f.front() == '+') f.remove_prefix(1);
            double v = 0;
            const auto [ptr, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
            if (f.empty() || ec == std::errc::invalid_argument || ptr != f.data() + f.size())
                throw Error(where(fileName, lineNo) + label + " is not a number");
            if (ec == std::errc::result_out_of_range) {
                // from_chars reports overflow and underflow alike; strtod tells them apart
                // (it returns HUGE_VAL on overflow and the rounded tiny value on underflow).
                v = std::strtod(std::string(f).c_str(), nullptr);
                if (std::isinf(v))
                    throw Error(where(fileName, lineNo) + label +
                                " is outside float range (|v| <= 3.4028235e38)");
            }
            if (!std::isfinite(v)) throw Error(where(fileName, lineNo) + label + " is not finite");
            // Values that round to the largest float are accepted; from the midpoint between it and
            // 2^128 on, the conversion would overflow.
            if (std::fabs(v) >= kFloatOverflow)
                throw Error(where(fileName, lineNo) + label +
                            " is outside float range (|v| <= 3.4028235e38)");
            row[k] = static_cast<float>(v);
        }
        out.pairs.push_back(row);
        out.lines.push_back(lineNo);
    }
    return out;
}

TriPairCsv readTriPairCsv(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path.string() + ": cannot open file");
    std::ostringstream ss;
    ss << in.rdbuf();
    return parseTriPairCsv(ss.str(), path.string());
}

} // namespace glcollide
