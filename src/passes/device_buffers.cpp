#include "passes/device_buffers.hpp"

#include <glcollide/error.hpp>

#include <array>
#include <string>
#include <utility>

namespace glcollide::passes {
namespace {

constexpr std::array<const char*, kBufferIdCount> kBufferLabels = {
    "positions",         "velocities",        "faces",          "forces",
    "springs",           "nodeSpringOffsets", "nodeSpringList", "heavyNodes",
    "nodeFaceOffsets",   "nodeFaceList",      "contactForces",  "health",
    "predictedPositions"};

template <typename F> void forEach(const DeviceBuffers& b, F&& f) {
    for (std::size_t i = 0; i < kBufferIdCount; ++i)
        if (const gl::Buffer& buffer = b[static_cast<BufferId>(i)]) f(buffer);
}

} // namespace

const char* bufferLabel(BufferId id) {
    return kBufferLabels[static_cast<std::size_t>(id)];
}

gl::Buffer& DeviceBuffers::operator[](BufferId id) {
    return const_cast<gl::Buffer&>(std::as_const(*this)[id]);
}

const gl::Buffer& DeviceBuffers::operator[](BufferId id) const {
    switch (id) {
    case BufferId::Positions:
        return positions;
    case BufferId::Velocities:
        return velocities;
    case BufferId::Faces:
        return faces;
    case BufferId::Forces:
        return forces;
    case BufferId::Springs:
        return springs;
    case BufferId::NodeSpringOffsets:
        return nodeSpringOffsets;
    case BufferId::NodeSpringList:
        return nodeSpringList;
    case BufferId::HeavyNodes:
        return heavyNodes;
    case BufferId::NodeFaceOffsets:
        return nodeFaceOffsets;
    case BufferId::NodeFaceList:
        return nodeFaceList;
    case BufferId::ContactForces:
        return contactForces;
    case BufferId::Health:
        return health;
    case BufferId::PredictedPositions:
        return predictedPositions;
    }
    throw Error("DeviceBuffers: unknown buffer id " + std::to_string(static_cast<int>(id)));
}

std::vector<std::string> DeviceBuffers::allocatedLabels() const {
    std::vector<std::string> labels;
    forEach(*this, [&](const gl::Buffer& b) { labels.push_back(b.label()); });
    return labels;
}

std::size_t DeviceBuffers::allocatedBytes() const {
    std::size_t bytes = 0;
    forEach(*this, [&](const gl::Buffer& b) { bytes += b.bytes(); });
    return bytes;
}

void bindRequired(const gl::Buffer& buffer, std::uint32_t binding, const char* pass, const char* what) {
    if (!buffer) throw Error(std::string(pass) + ": buffer '" + what + "' was not allocated");
    buffer.bindStorage(binding);
}

} // namespace glcollide::passes
