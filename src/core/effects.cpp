#include <glcollide/effects.hpp>

#include <array>
#include <utility>

namespace glcollide {
namespace {
constexpr std::array<std::pair<Effect, std::string_view>, 7> kNames{{
    {Effect::Gravity, "gravity"},
    {Effect::Springs, "springs"},
    {Effect::Damping, "damping"},
    {Effect::Wind, "wind"},
    {Effect::Ground, "ground"},
    {Effect::Collisions, "collisions"},
    {Effect::SelfCollisions, "self_collisions"},
}};
} // namespace

std::string_view effectName(Effect effect) {
    for (const auto& [e, name] : kNames)
        if (e == effect) return name;
    return "unknown";
}

std::optional<Effect> parseEffect(std::string_view name) {
    for (const auto& [e, n] : kNames)
        if (n == name) return e;
    return std::nullopt;
}

std::vector<Effect> EffectSet::list() const {
    std::vector<Effect> out;
    for (Effect e : kAllEffects)
        if (has(e)) out.push_back(e);
    return out;
}

} // namespace glcollide
