#pragma once
// The flat model of a few bodies, for the model and twin tests.

#include "model/flat_model.hpp"

#include <glcollide/scene.hpp>

#include <vector>

namespace glcollide::test {

inline model::FlatModel modelOf(const std::vector<Body>& bodies) {
    Scene scene;
    scene.bodies = bodies;
    return model::flatten(scene);
}

} // namespace glcollide::test
