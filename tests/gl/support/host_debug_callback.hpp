#pragma once
// A stand-in for a host application's GL debug callback, installed before glcollide's, and a
// fixture base that installs it for one test and puts the environment's callback back after.
// Shared by debug_output_gl_test.cpp and host_context_gl_test.cpp.

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

namespace glcollide::test {

struct HostLog {
    std::vector<std::string> messages;
};

inline void GLAPIENTRY hostCallback(GLenum, GLenum, GLuint, GLenum, GLsizei length, const GLchar* message,
                                    const void* userParam) {
    auto* log = static_cast<HostLog*>(const_cast<void*>(userParam));
    log->messages.emplace_back(message, static_cast<std::size_t>(length < 0 ? std::strlen(message) : length));
}

class HostDebugCallbackTest : public ::testing::Test {
  protected:
    void SetUp() override {
        glGetPointerv(GL_DEBUG_CALLBACK_FUNCTION, &m_envCallback);
        glGetPointerv(GL_DEBUG_CALLBACK_USER_PARAM, &m_envParam);
        glDebugMessageCallback(&hostCallback, &m_host);
    }
    void TearDown() override {
        glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS); // the test environment's setting
        glDebugMessageCallback(reinterpret_cast<GLDEBUGPROC>(m_envCallback), m_envParam);
    }

    HostLog m_host;
    void* m_envCallback = nullptr;
    void* m_envParam = nullptr;
};

} // namespace glcollide::test
