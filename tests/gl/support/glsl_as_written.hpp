#pragma once
// Whether the current context's compiler evaluates float GLSL as written (no contraction, no
// reordering), so that a kernel's rounding-dependent outputs equal its C++ twin's bit for bit.
// llvmpipe does (every twin comparison passes there); an NVIDIA H200 at bd8506c did not (the CCD's
// box count differed from the twin's with the same answers). Tests compare such outputs with the
// twin only where this holds, and check what the method guarantees on every device.

#include <glcollide/gl_info.hpp>

#include <string>

namespace glcollide::test {

inline bool deviceEvaluatesGlslAsWritten() {
    return queryGlInfo().renderer.find("llvmpipe") != std::string::npos;
}

} // namespace glcollide::test
