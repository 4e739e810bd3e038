// DebugOutputScope chaining/restoring, labels and debug groups on the test context.

#include "gl/debug_output.hpp"
#include "support/gl_test_environment.hpp"
#include "support/host_debug_callback.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <string>
#include <vector>

namespace glcollide {
namespace {

using test::hostCallback;

// Installs hostCallback for the test and puts the environment's callback back afterwards.
class DebugOutput : public test::HostDebugCallbackTest {
  protected:
    void insert(const std::string& text, GLuint id = 42) {
        glDebugMessageInsert(GL_DEBUG_SOURCE_THIRD_PARTY, GL_DEBUG_TYPE_OTHER, id, GL_DEBUG_SEVERITY_MEDIUM,
                             static_cast<GLsizei>(text.size()), text.c_str());
    }
};

TEST_F(DebugOutput, ScopeReceivesAndChainsToPreviousCallback) {
    std::vector<gl::DebugMessage> received;
    std::vector<std::string> texts;
    {
        gl::DebugOutputScope scope(
            [&](const gl::DebugMessage& m) {
                received.push_back(m);
                texts.emplace_back(m.text);
            },
            gl::DebugOutputScope::kEnableOutput | gl::DebugOutputScope::kSynchronous);
        EXPECT_EQ(scope.previousCallback(), &hostCallback);
        EXPECT_EQ(scope.previousUserParam(), &m_host);
        insert("glcollide chained message", 7);
        glFinish();
        ASSERT_EQ(texts.size(), 1u);
        EXPECT_EQ(texts[0], "glcollide chained message");
        EXPECT_EQ(received[0].source, static_cast<GLenum>(GL_DEBUG_SOURCE_THIRD_PARTY));
        EXPECT_EQ(received[0].type, static_cast<GLenum>(GL_DEBUG_TYPE_OTHER));
        EXPECT_EQ(received[0].id, 7u);
        EXPECT_EQ(received[0].severity, static_cast<GLenum>(GL_DEBUG_SEVERITY_MEDIUM));
        ASSERT_EQ(m_host.messages.size(), 1u);
        EXPECT_EQ(m_host.messages[0], "glcollide chained message");
    }
    // Restored: the host's callback and parameter are back, and only the host sees new messages.
    void* callback = nullptr;
    void* param = nullptr;
    glGetPointerv(GL_DEBUG_CALLBACK_FUNCTION, &callback);
    glGetPointerv(GL_DEBUG_CALLBACK_USER_PARAM, &param);
    EXPECT_EQ(reinterpret_cast<GLDEBUGPROC>(callback), &hostCallback);
    EXPECT_EQ(param, &m_host);
    insert("after the scope");
    glFinish();
    EXPECT_EQ(texts.size(), 1u);
    ASSERT_EQ(m_host.messages.size(), 2u);
    EXPECT_EQ(m_host.messages[1], "after the scope");
}

TEST_F(DebugOutput, NestedScopesRestoreInOrder) {
    int outer = 0, inner = 0;
    {
        gl::DebugOutputScope first([&](const gl::DebugMessage&) { ++outer; });
        {
            gl::DebugOutputScope second([&](const gl::DebugMessage&) { ++inner; });
            insert("both");
        }
        insert("outer only");
    }
    EXPECT_EQ(inner, 1);
    EXPECT_EQ(outer, 2);
    EXPECT_EQ(m_host.messages.size(), 2u);
}

TEST_F(DebugOutput, DebugGroupIsThirdPartyPushAndPop) {
    std::vector<gl::DebugMessage> groups;
    std::vector<std::string> names;
    gl::DebugOutputScope scope([&](const gl::DebugMessage& m) {
        if (m.type == GL_DEBUG_TYPE_PUSH_GROUP || m.type == GL_DEBUG_TYPE_POP_GROUP) {
            groups.push_back(m);
            names.emplace_back(m.text);
        }
    });
    GLint depthBefore = 0, depthInside = 0, depthAfter = 0;
    glGetIntegerv(GL_DEBUG_GROUP_STACK_DEPTH, &depthBefore);
    {
        gl::DebugGroup group("glcollide/NodeForce", 3);
        glGetIntegerv(GL_DEBUG_GROUP_STACK_DEPTH, &depthInside);
    }
    glGetIntegerv(GL_DEBUG_GROUP_STACK_DEPTH, &depthAfter);
    EXPECT_EQ(depthInside, depthBefore + 1);
    EXPECT_EQ(depthAfter, depthBefore);
    ASSERT_EQ(groups.size(), 2u);
    EXPECT_EQ(groups[0].type, static_cast<GLenum>(GL_DEBUG_TYPE_PUSH_GROUP));
    EXPECT_EQ(groups[0].source, static_cast<GLenum>(GL_DEBUG_SOURCE_THIRD_PARTY));
    EXPECT_EQ(names[0], "glcollide/NodeForce");
    EXPECT_EQ(groups[1].type, static_cast<GLenum>(GL_DEBUG_TYPE_POP_GROUP));
}

TEST(DebugGroup, FullStackDoesNotOverflow) {
    GLint maxDepth = 0;
    glGetIntegerv(GL_MAX_DEBUG_GROUP_STACK_DEPTH, &maxDepth);
    ASSERT_GT(maxDepth, 1);
    GLint initialDepth = 0; // the default group counts: 1 outside any push
    glGetIntegerv(GL_DEBUG_GROUP_STACK_DEPTH, &initialDepth);
    std::vector<std::unique_ptr<gl::DebugGroup>> groups;
    // One more than fits: the last one must be a no-op, not GL_STACK_OVERFLOW (the environment
    // fails the test on any GL error).
    for (GLint i = 0; i < maxDepth + 1; ++i) groups.push_back(std::make_unique<gl::DebugGroup>("deep"));
    GLint depth = 0;
    glGetIntegerv(GL_DEBUG_GROUP_STACK_DEPTH, &depth);
    EXPECT_EQ(depth, maxDepth);
    while (!groups.empty()) groups.pop_back();
    glGetIntegerv(GL_DEBUG_GROUP_STACK_DEPTH, &depth);
    EXPECT_EQ(depth, initialDepth);
}

TEST(LabelObject, RoundTripsAndTruncates) {
    GLuint buffer = 0;
    glGenBuffers(1, &buffer);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffer);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    gl::labelObject(GL_BUFFER, buffer, "glcollide/positions");
    char label[1024] = {};
    GLsizei length = 0;
    glGetObjectLabel(GL_BUFFER, buffer, sizeof label, &length, label);
    EXPECT_EQ(std::string(label, static_cast<std::size_t>(length)), "glcollide/positions");

    GLint maxLength = 0;
    glGetIntegerv(GL_MAX_LABEL_LENGTH, &maxLength);
    const std::string tooLong(static_cast<std::size_t>(maxLength) + 50, 'x');
    gl::labelObject(GL_BUFFER, buffer, tooLong);
    glGetObjectLabel(GL_BUFFER, buffer, sizeof label, &length, label);
    EXPECT_EQ(length, maxLength - 1);
    glDeleteBuffers(1, &buffer);
}

TEST(GlErrorRecording, ProvokedErrorIsCountedWhenExpected) {
    test::ExpectGlErrors expected;
    glBindBuffer(GL_SHADER_STORAGE_BUFFER + 1, 0); // GL_INVALID_ENUM on purpose
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
    EXPECT_EQ(expected.count(), 1u);
}

} // namespace
} // namespace glcollide
