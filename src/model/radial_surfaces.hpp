#pragma once
// Which objects radial view-based culling may give an observer (decision 0025, "The premise"):
// the theorem needs a closed, consistently oriented, connected surface — closed so that it winds
// around the observer, oriented so that the winding number is ±1 and not a mix, connected so that
// nested components cannot wind twice around it. GL-free.

#include <cstdint>
#include <vector>

namespace glcollide::model {

/// True when faces [firstFace, firstFace + faceCount) of `faceIndices` (3 nodes per face) form one
/// surface whose every directed edge a→b appears in exactly one face and b→a in exactly one other
/// (closed and consistently oriented), and which is connected through its edges. False for no faces.
bool isClosedOrientedConnected(const std::vector<std::uint32_t>& faceIndices, std::uint32_t firstFace,
                               std::uint32_t faceCount);

} // namespace glcollide::model
