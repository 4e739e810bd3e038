#pragma once
/// \file Error type thrown for setup problems: bad scenes or meshes, no EGL, GL < 4.3, shader errors.

#include <stdexcept>
#include <string>

namespace glcollide {

/// Thrown by setup code (loading, context creation, shader compilation, engine construction).
/// The message names the file and the line or JSON pointer where that applies, and what is wrong.
/// The step loop throws only when a collision pair list would outgrow the device (Engine::step),
/// or when robust TriTri's exact pass could not finish a pair (a broken library assumption);
/// other device-side problems (non-finite states) are reported in the step statistics.
class Error : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

} // namespace glcollide
