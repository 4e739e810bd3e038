// ComputeProgram's uniform setters: the active uniforms are read once when a program is built
// (src/gl/program.cpp); a setter writes the value a kernel then reads, refuses a value of the wrong
// type with an error naming the program and the uniform, and ignores a name that is not active.

#include "gl/program.hpp"

#include <glcollide/error.hpp>

#include <gtest/gtest.h>

#include <epoxy/gl.h>

#include <array>
#include <string>

namespace glcollide {
namespace {

constexpr const char* kSource = R"(#version 430
layout(local_size_x = 1) in;
layout(std430, binding = 0) buffer Out { float values[]; };
uniform float u_scale;
uniform uint u_count;
uniform vec3 u_offset;
void main() {
    values[0] = u_scale;
    values[1] = float(u_count);
    values[2] = u_offset.x;
    values[3] = u_offset.y;
    values[4] = u_offset.z;
}
)";

TEST(ProgramUniformsGl, SettersWriteWhatTheKernelReads) {
    const gl::ComputeProgram program = gl::ComputeProgram::fromSource("uniform_probe", kSource);
    const std::array<float, 5> zeros{};
    const gl::Buffer out("uniformProbe", sizeof zeros, zeros.data());
    out.bindStorage(0);
    program.use();
    program.set("u_scale", 2.5f);
    program.set("u_count", 7u);
    program.set("u_offset", glm::dvec3(-1.0, 0.25, 1e6));
    program.set("u_not_declared", 1.0f); // not active: ignored, as GL ignores location -1
    gl::ComputeProgram::dispatch(1, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::array<float, 5> got{};
    out.download(0, sizeof got, got.data());
    // Every value is exactly representable in float: the kernel must see it unchanged.
    EXPECT_EQ(got, (std::array<float, 5>{2.5f, 7.0f, -1.0f, 0.25f, 1e6f}));
}

TEST(ProgramUniformsGl, AValueOfTheWrongTypeIsAnErrorNamingTheUniform) {
    const gl::ComputeProgram program = gl::ComputeProgram::fromSource("uniform_probe", kSource);
    try {
        program.set("u_scale", 3u); // a float uniform set as uint
        ADD_FAILURE() << "expected an error";
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("uniform_probe"), std::string::npos) << what;
        EXPECT_NE(what.find("u_scale"), std::string::npos) << what;
    }
    EXPECT_THROW(program.set("u_count", 1.0f), Error);
    EXPECT_THROW(program.set("u_offset", 1.0f), Error);
    EXPECT_THROW(program.set("u_scale", glm::dvec3(1.0)), Error);
}

} // namespace
} // namespace glcollide
