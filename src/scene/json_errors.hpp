#pragma once
/// \file One message for every way nlohmann-json can reject a document, shared by the scene and
/// benchmark-suite readers (fuzzing found that catching parse_error alone let the number-overflow
/// exception of "1e999" escape both).

#include <nlohmann/json.hpp>

#include <algorithm>
#include <string>

namespace glcollide::detail {

/// "<sourceName>: invalid JSON: ..." for a parse error (nlohmann names line and column), or for a
/// number beyond double range (nlohmann gives no position: the line of the token's first
/// occurrence in `text` is named), or any other nlohmann exception.
inline std::string invalidJsonMessage(const nlohmann::json::exception& e, const std::string& text,
                                      const std::string& sourceName) {
    std::string message = e.what();
    std::string where;
    if (dynamic_cast<const nlohmann::json::out_of_range*>(&e) != nullptr) {
        const std::size_t q0 = message.find('\'');
        const std::size_t q1 = q0 == std::string::npos ? q0 : message.find('\'', q0 + 1);
        if (q1 != std::string::npos) {
            const std::string token = message.substr(q0 + 1, q1 - q0 - 1);
            const std::size_t at = token.empty() ? std::string::npos : text.find(token);
            if (at != std::string::npos)
                where = "line " +
                        std::to_string(1 + std::count(text.begin(),
                                                      text.begin() + static_cast<std::ptrdiff_t>(at), '\n')) +
                        ": ";
            message =
                "number " + token + " is outside the range of a double (non-finite values are not allowed)";
        }
    }
    return sourceName + ": invalid JSON: " + where + message;
}

} // namespace glcollide::detail
