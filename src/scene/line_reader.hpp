#pragma once
/// \file A line-oriented text reader for the tet mesh formats: tracks the line number so every
/// parse error can name "file:line".

#include <glcollide/error.hpp>

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

namespace glcollide::detail {

/// std::from_chars rejects the leading '+' that C's strtod (and many exporters) accept: drop one
/// when a digit or '.' follows, so "+1.5" reads as 1.5 and "+" or "++1" stay errors.
inline std::string_view withoutLeadingPlus(std::string_view token) {
    if (token.size() >= 2 && token[0] == '+' && (token[1] == '.' || (token[1] >= '0' && token[1] <= '9')))
        token.remove_prefix(1);
    return token;
}

class LineReader {
  public:
    /// Reads the whole file; throws Error if it cannot be opened.
    explicit LineReader(const std::filesystem::path& path) : m_file(path.string()) {
        std::ifstream in(path, std::ios::binary);
        if (!in) throw Error(m_file + ": cannot open file");
        std::ostringstream ss;
        ss << in.rdbuf();
        m_text = ss.str();
    }

    /// The next line without its line terminator; false at end of file.
    bool next(std::string_view& line) {
        if (m_pos >= m_text.size()) return false;
        std::size_t end = m_text.find('\n', m_pos);
        if (end == std::string::npos) end = m_text.size();
        line = std::string_view(m_text).substr(m_pos, end - m_pos);
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        m_pos = end + 1;
        ++m_line;
        return true;
    }

    /// The next line that is not blank once `comment` and what follows it are removed (TetGen
    /// style). Returns its tokens; empty at end of file.
    std::vector<std::string_view> nextData(char comment) {
        std::string_view line;
        while (next(line)) {
            if (auto c = line.find(comment); c != std::string_view::npos) line = line.substr(0, c);
            auto tokens = split(line);
            if (!tokens.empty()) return tokens;
        }
        return {};
    }

    /// The next line's tokens; throws "unexpected end of file" at the end, saying what was expected.
    std::vector<std::string_view> require(const std::string& expected) {
        std::string_view line;
        if (!next(line)) failAtEnd("unexpected end of file, expected " + expected);
        return split(line);
    }

    static std::vector<std::string_view> split(std::string_view line) {
        std::vector<std::string_view> out;
        std::size_t i = 0;
        while (i < line.size()) {
            while (i < line.size() && isSpace(line[i])) ++i;
            std::size_t j = i;
            while (j < line.size() && !isSpace(line[j])) ++j;
            if (j > i) out.push_back(line.substr(i, j - i));
            i = j;
        }
        return out;
    }

    [[noreturn]] void fail(const std::string& message) const {
        throw Error(m_file + ":" + std::to_string(m_line) + ": " + message);
    }
    [[noreturn]] void failAtEnd(const std::string& message) const {
        throw Error(m_file + ":" + std::to_string(m_line) + ": " + message);
    }

    /// Parses a whole token as an integer; `what` names it in the error.
    long long toInt(std::string_view token, const std::string& what) const {
        long long v = 0;
        const std::string_view digits = withoutLeadingPlus(token);
        const auto [p, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), v);
        if (ec != std::errc() || p != digits.data() + digits.size())
            fail("expected an integer " + what + ", got '" + std::string(token) + "'");
        return v;
    }
    /// Parses a whole token as a finite floating-point number.
    double toDouble(std::string_view token, const std::string& what) const {
        double v = 0.0;
        const std::string_view digits = withoutLeadingPlus(token);
        const auto [p, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), v);
        if (ec != std::errc() || p != digits.data() + digits.size())
            fail("expected a number " + what + ", got '" + std::string(token) + "'");
        if (!std::isfinite(v)) fail("non-finite " + what + " '" + std::string(token) + "'");
        return v;
    }
    /// Checks that a line has at least `n` tokens.
    void expectTokens(const std::vector<std::string_view>& tokens, std::size_t n,
                      const std::string& what) const {
        if (tokens.size() < n)
            fail("expected " + what + " (" + std::to_string(n) + " values), got " +
                 std::to_string(tokens.size()) + " value(s)");
    }

    [[nodiscard]] std::size_t line() const { return m_line; }
    [[nodiscard]] const std::string& file() const { return m_file; }

  private:
    static bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

    std::string m_file;
    std::string m_text;
    std::size_t m_pos = 0;
    std::size_t m_line = 0;
};

} // namespace glcollide::detail
