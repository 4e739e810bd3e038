#pragma once
/// \file The effects a scene may list. The engine composes its pass list from them: a pass whose
/// effect is absent is neither dispatched nor allocated.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace glcollide {

enum class Effect : std::uint8_t {
    Gravity,        ///< constant acceleration `Scene::gravity` (NodeForce)
    Springs,        ///< Hooke springs with damping along the spring (SpringUpdate)
    Damping,        ///< viscous air damping, -c·m·v per node (NodeForce)
    Wind,           ///< linear aerodynamic drag of faces in a constant wind (NodeForce)
    Ground,         ///< a horizontal ground plane with restitution and friction (NodeUpdate)
    Collisions,     ///< contacts between objects (not implemented yet: rejected with an Error)
    SelfCollisions, ///< contacts within an object: faces that share no node
};

inline constexpr Effect kAllEffects[] = {Effect::Gravity,       Effect::Springs, Effect::Damping,
                                         Effect::Wind,          Effect::Ground,  Effect::Collisions,
                                         Effect::SelfCollisions};

/// The scene-file name of an effect ("gravity", "springs", "damping", "wind", "ground",
/// "collisions", "self_collisions").
std::string_view effectName(Effect effect);
/// Inverse of effectName; nullopt for an unknown name.
std::optional<Effect> parseEffect(std::string_view name);

/// A small set of effects.
class EffectSet {
  public:
    EffectSet() = default;
    EffectSet(std::initializer_list<Effect> effects) {
        for (Effect e : effects) insert(e);
    }
    void insert(Effect e) { m_bits |= bit(e); }
    void erase(Effect e) { m_bits &= static_cast<std::uint32_t>(~bit(e)); }
    [[nodiscard]] bool has(Effect e) const { return (m_bits & bit(e)) != 0; }
    [[nodiscard]] bool empty() const { return m_bits == 0; }
    /// The effects in declaration order.
    [[nodiscard]] std::vector<Effect> list() const;
    friend bool operator==(EffectSet, EffectSet) = default;

  private:
    static std::uint32_t bit(Effect e) { return 1u << static_cast<unsigned>(e); }
    std::uint32_t m_bits = 0;
};

} // namespace glcollide
