#include "passes/device_buffers.hpp"

#include <glcollide/error.hpp>

namespace glcollide::passes {
namespace {
template <typename F> void forEach(const DeviceBuffers& b, F&& f) {
    for (const gl::Buffer* buffer :
         {&b.positions, &b.velocities, &b.faces, &b.forces, &b.springs, &b.nodeSpringOffsets,
          &b.nodeSpringList, &b.heavyNodes, &b.nodeFaceOffsets, &b.nodeFaceList, &b.contactForces, &b.health})
        if (*buffer) f(*buffer);
}
} // namespace

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
