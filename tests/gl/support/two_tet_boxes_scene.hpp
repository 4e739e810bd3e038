#pragma once
// The smallest colliding scene: two one-cell tet boxes overlapping by half, springs and collisions
// with the given narrow-phase precision. Tests of set-up (program cache, robust self-check) build
// engines from it.

#include <glcollide/scene.hpp>

#include <string>

namespace glcollide::test {

inline Scene twoOverlappingTetBoxes(const std::string& precision) {
    const std::string json = R"({"format_version": 1, "name": "two tet boxes",
      "effects": ["springs", "collisions"], "collision": {"response": "penalty", "precision": ")" +
                             precision + R"("},
      "objects": [
        {"name": "a", "generator": {"type": "tet_box", "size": [1, 1, 1], "resolution": [1, 1, 1]},
         "mass": 1, "springs": {"stiffness": 10}},
        {"name": "b", "generator": {"type": "tet_box", "size": [1, 1, 1], "resolution": [1, 1, 1]},
         "transform": {"translate": [0.5, 0, 0]}, "mass": 1, "springs": {"stiffness": 10}}]})";
    return parseScene(json, ".", "two tet boxes");
}

} // namespace glcollide::test
