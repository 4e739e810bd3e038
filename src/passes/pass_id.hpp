#pragma once
// The engine's passes: one identifier each, their names stated once. Timer sections, debug groups,
// statistics and the pipeline plan all index by PassId, so no list of names is reconciled with
// another at run time.

#include <array>
#include <cstddef>
#include <cstdint>

namespace glcollide::passes {

/// In pipeline order (a substep dispatches them in this order when its scene calls for them).
enum class PassId : std::uint8_t {
    NodeForce,
    SpringUpdate,
    BBUpdate,
    BBCollision,
    TriTri,
    ContactResponse,
    NodeUpdate
};

inline constexpr std::size_t kPassCount = 7;

inline constexpr std::array<const char*, kPassCount> kPassNames = {
    "NodeForce", "SpringUpdate", "BBUpdate", "BBCollision", "TriTri", "ContactResponse", "NodeUpdate"};

constexpr const char* passName(PassId id) {
    return kPassNames[static_cast<std::size_t>(id)];
}
constexpr std::size_t passIndex(PassId id) {
    return static_cast<std::size_t>(id);
}

} // namespace glcollide::passes
