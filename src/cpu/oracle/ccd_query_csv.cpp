#include "cpu/oracle/ccd_query_csv.hpp"

#include <glcollide/error.hpp>

#include <fstream>
#include <sstream>

namespace glcollide::cpu {
namespace {

std::string_view trim(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
    return s;
}

bool isDigit(char c) {
    return c >= '0' && c <= '9';
}

/// [+-]digits, nothing else (mpz_class::set_str alone would also take inner spaces).
std::optional<mpz_class> parseExactInteger(std::string_view text) {
    std::string_view digits = text;
    if (!digits.empty() && (digits.front() == '+' || digits.front() == '-')) digits.remove_prefix(1);
    if (digits.empty()) return std::nullopt;
    for (char c : digits)
        if (!isDigit(c)) return std::nullopt;
    mpz_class value(std::string(digits), 10);
    if (text.front() == '-') value = -value;
    return value;
}

/// The smallest magnitude that rounds to infinity in float: 2^128 - 2^103, halfway between the
/// largest float (2^128 - 2^104) and 2^128 (round to nearest, ties to even, goes up there).
const mpq_class& floatOverflowThreshold() {
    static const mpq_class threshold = [] {
        mpz_class t = 1;
        t <<= 128;
        mpz_class half = 1;
        half <<= 103;
        return mpq_class(t - half);
    }();
    return threshold;
}

struct Location {
    const std::string& file;
    std::size_t line;
    [[noreturn]] void fail(const std::string& what) const {
        throw Error(file + ":" + std::to_string(line) + ": " + what);
    }
};

std::string fieldLabel(std::size_t index, std::string_view text) {
    return "field " + std::to_string(index + 1) + " '" + std::string(text) + "'";
}

void checkFloatRange(const mpq_class& value, std::size_t index, std::string_view text, const Location& at) {
    if (abs(value) >= floatOverflowThreshold())
        at.fail(fieldLabel(index, text) + " is outside float range (|v| <= 3.4028235e38)");
}

/// x, y and z of one row of 6 integer fields (numerator, denominator pairs).
RationalPoint rationalRow(const std::vector<std::string_view>& fields, const Location& at) {
    mpq_class coords[3];
    for (std::size_t k = 0; k < 3; ++k) {
        const std::optional<mpz_class> num = parseExactInteger(fields[2 * k]);
        if (!num) at.fail(fieldLabel(2 * k, fields[2 * k]) + " is not an integer");
        const std::optional<mpz_class> den = parseExactInteger(fields[2 * k + 1]);
        if (!den) at.fail(fieldLabel(2 * k + 1, fields[2 * k + 1]) + " is not an integer");
        if (sgn(*den) <= 0)
            at.fail(fieldLabel(2 * k + 1, fields[2 * k + 1]) + " is not a positive denominator");
        coords[k] = mpq_class(*num, *den);
        coords[k].canonicalize();
        checkFloatRange(coords[k], 2 * k, std::string(fields[2 * k]) + "/" + std::string(fields[2 * k + 1]),
                        at);
    }
    return {coords[0], coords[1], coords[2]};
}

/// x, y and z of one row of 3 decimal fields.
RationalPoint decimalRow(const std::vector<std::string_view>& fields, const Location& at) {
    mpq_class coords[3];
    for (std::size_t k = 0; k < 3; ++k) {
        const std::optional<mpq_class> value = parseExactDecimal(fields[k]);
        if (!value) at.fail(fieldLabel(k, fields[k]) + " is not a decimal number");
        coords[k] = *value;
        checkFloatRange(coords[k], k, fields[k], at);
    }
    return {coords[0], coords[1], coords[2]};
}

std::vector<std::string_view> splitFields(std::string_view line) {
    std::vector<std::string_view> fields;
    for (std::size_t start = 0;;) {
        const std::size_t comma = line.find(',', start);
        fields.push_back(trim(
            line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start)));
        if (comma == std::string_view::npos) return fields;
        start = comma + 1;
    }
}

/// The ground-truth field: 0 or 1.
bool truthField(std::size_t index, std::string_view text, const Location& at) {
    if (text == "0") return false;
    if (text == "1") return true;
    at.fail(fieldLabel(index, text) + " (ground truth) is not 0 or 1");
}

} // namespace

std::optional<mpq_class> parseExactDecimal(std::string_view text) {
    std::size_t i = 0;
    bool negative = false;
    if (i < text.size() && (text[i] == '+' || text[i] == '-')) negative = text[i++] == '-';
    std::string digits; // the significand's digits, point removed
    long fractionDigits = 0;
    bool anyDigit = false;
    while (i < text.size() && isDigit(text[i])) {
        digits += text[i++];
        anyDigit = true;
    }
    if (i < text.size() && text[i] == '.') {
        ++i;
        while (i < text.size() && isDigit(text[i])) {
            digits += text[i++];
            ++fractionDigits;
            anyDigit = true;
        }
    }
    if (!anyDigit) return std::nullopt;
    long exponent = 0;
    if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
        ++i;
        bool negativeExponent = false;
        if (i < text.size() && (text[i] == '+' || text[i] == '-')) negativeExponent = text[i++] == '-';
        if (i == text.size()) return std::nullopt;
        for (; i < text.size() && isDigit(text[i]); ++i) {
            exponent = exponent * 10 + (text[i] - '0');
            if (exponent > 100000) return std::nullopt; // beyond any float: refused, not computed
        }
        if (negativeExponent) exponent = -exponent;
    }
    if (i != text.size()) return std::nullopt;
    mpz_class significand(digits, 10);
    if (negative) significand = -significand;
    if (sgn(significand) == 0) return mpq_class(0);
    const long power = exponent - fractionDigits; // value = significand * 10^power
    mpz_class scale;
    mpz_ui_pow_ui(scale.get_mpz_t(), 10, static_cast<unsigned long>(power < 0 ? -power : power));
    mpq_class value = power < 0 ? mpq_class(significand, scale) : mpq_class(significand * scale);
    value.canonicalize();
    return value;
}

std::vector<CcdCsvQuery> parseCcdQueryCsv(std::string_view text, const std::string& fileName) {
    std::vector<CcdCsvQuery> queries;
    int row = 0; // rows of the current query read so far (0..7)
    std::size_t lineNo = 0, pos = 0;
    while (pos < text.size()) {
        std::size_t end = text.find('\n', pos);
        if (end == std::string_view::npos) end = text.size();
        const std::string_view line = trim(text.substr(pos, end - pos));
        pos = end + 1;
        ++lineNo;
        if (line.empty() || line.front() == '#') continue;

        const Location at{fileName, lineNo};
        const std::vector<std::string_view> fields = splitFields(line);
        const std::size_t n = fields.size();
        if (n != 3 && n != 4 && n != 6 && n != 7)
            at.fail("expected x,y,z as 6 integers (numerator,denominator pairs) or 3 decimal numbers, "
                    "optionally followed by the ground truth 0 or 1; got " +
                    std::to_string(n) + " field" + (n == 1 ? "" : "s"));
        const bool integers = n >= 6;
        const bool hasTruth = n == 4 || n == 7;
        if (row == 0) queries.emplace_back();
        CcdCsvQuery& query = queries.back();
        query.points[static_cast<std::size_t>(row)] =
            integers ? rationalRow(fields, at) : decimalRow(fields, at);
        query.lines[static_cast<std::size_t>(row)] = lineNo;
        const std::optional<bool> truth =
            hasTruth ? std::optional<bool>(truthField(n - 1, fields[n - 1], at)) : std::nullopt;
        if (row == 0) {
            query.truth = truth;
        } else if (truth.has_value() != query.truth.has_value()) {
            at.fail(std::string("the ground-truth column is ") +
                    (hasTruth ? "here but not" : "missing here but") + " on line " +
                    std::to_string(query.lines[0]) + ", the query's first row");
        } else if (truth && *truth != *query.truth) {
            at.fail("ground truth " + std::to_string(int(*truth)) + " differs from line " +
                    std::to_string(query.lines[0]) + " of the same query (" +
                    std::to_string(int(*query.truth)) + ")");
        }
        row = (row + 1) % 8;
    }
    if (row != 0)
        Location{fileName, queries.back().lines[0]}.fail(
            "the file ends inside this query: " + std::to_string(row) +
            " of its 8 rows (4 points at t = 0, then the same 4 at t = 1)");
    return queries;
}

std::vector<CcdCsvQuery> readCcdQueryCsv(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path.string() + ": cannot open file");
    std::ostringstream ss;
    ss << in.rdbuf();
    return parseCcdQueryCsv(ss.str(), path.string());
}

} // namespace glcollide::cpu
