#pragma once
// Compute programs built from the shaders embedded at build time.

#include "gl/handles.hpp"

#include <cstdint>
#include <glm/vec3.hpp>

#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace glcollide::gl {

/// Names of all embedded shaders (stems of shaders/passes/*.comp and shaders/bench/*.comp).
std::vector<std::string> embeddedShaderNames();

/// The feature switches a shader declares (`// glcollide-features:`); the only GLC_ defines it
/// accepts. Throws Error for an unknown name.
std::vector<std::string> shaderFeatures(std::string_view name);

/// The expanded source of an embedded shader with `defines` ("NAME" or "NAME VALUE") inserted
/// after #version. Throws Error for an unknown name.
std::string shaderSource(std::string_view name, const std::vector<std::string>& defines = {});

/// Rewrites a driver's compile log so "S:L(C)" (Mesa) and "S(L)" (NVIDIA) locations, where S is
/// the GLSL source-string number of a #line marker, read "<file>:L".
std::string mapShaderLog(const std::string& log, std::string_view shaderName);

/// A linked compute program. Compile and link errors throw Error with the mapped log.
class ComputeProgram {
  public:
    ComputeProgram() = default;
    ComputeProgram(std::string_view shaderName, const std::vector<std::string>& defines = {});
    /// A program from complete GLSL text that is not an embedded shader (tests, probes); its
    /// compile log is reported unmapped.
    static ComputeProgram fromSource(std::string label, const std::string& source);

    [[nodiscard]] GLname name() const { return m_handle.name(); }
    [[nodiscard]] const std::string& shaderName() const { return m_shaderName; }
    void use() const;
    /// Uniform setters on this program (glProgramUniform*). The program's active uniforms, their
    /// locations and types, are read once when it is built; a setter finds the name among them
    /// (no driver call) and throws Error when the value's type is not the uniform's (a float set
    /// as uint would reinterpret the bits on some drivers and be dropped by others). A name that is
    /// not active (unknown, or optimised away in this variant) is ignored, as GL does for
    /// location -1.
    void set(const char* uniform, float value) const;
    void set(const char* uniform, std::uint32_t value) const;
    void set(const char* uniform, const glm::dvec3& value) const;
    /// glDispatchCompute with enough groups of `groupSize` to cover `invocations` (x only; more
    /// than 65535 groups spill into y, and the shader folds y back into its index).
    void dispatch1D(std::uint32_t invocations, std::uint32_t groupSize) const;
    /// glDispatchCompute(x, y, z), counted by dispatchCount().
    static void dispatch(std::uint32_t x, std::uint32_t y, std::uint32_t z);
    /// glDispatchComputeIndirect at `offset` of the bound GL_DISPATCH_INDIRECT_BUFFER, counted.
    static void dispatchIndirect(std::intptr_t offset);

  private:
    /// Loads the program from the program binary cache (gl/program_cache.hpp) or compiles and
    /// links it (then stores it there), and records the cost in the active SetupStats sink.
    void build(const std::string& source, const std::vector<std::string>& defines,
               const std::function<std::string(const std::string&)>& mapLog);
    [[nodiscard]] Handle<deleteProgram>
    compileAndLink(const std::string& source, const std::function<std::string(const std::string&)>& mapLog,
                   bool retrievable) const;

    struct ActiveUniform {
        std::string name;
        std::int32_t location;
        std::uint32_t type; // GLenum: GL_FLOAT, GL_UNSIGNED_INT, GL_FLOAT_VEC3, ...
    };
    void readActiveUniforms();
    /// The active uniform `uniform` of type `type`, or nullptr when it is not active.
    [[nodiscard]] const ActiveUniform* find(const char* uniform, std::uint32_t type) const;

    Handle<deleteProgram> m_handle;
    std::string m_shaderName;
    std::vector<ActiveUniform> m_uniforms;
};

/// Compute dispatches issued through ComputeProgram since the process started (GL is used from one
/// thread). The engine reports dispatches per substep from its differences: launch count is a
/// cost of its own on a GPU (docs/integration.md).
std::uint64_t dispatchCount();

} // namespace glcollide::gl
