// Buffers beyond what a shader can address are refused by name (docs/reliability.md): every
// engine buffer is bound whole as a shader storage block, and a block larger than
// GL_MAX_SHADER_STORAGE_BLOCK_SIZE would allocate but be read wrongly.
#include "gl/handles.hpp"

#include <glcollide/error.hpp>

#include <epoxy/gl.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <string>

namespace glcollide {
namespace {

std::uint64_t storageBlockLimit() {
    GLint64 limit = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &limit);
    return static_cast<std::uint64_t>(limit);
}

TEST(BufferLimits, ABufferBeyondTheStorageBlockLimitIsRefusedByName) {
    const std::uint64_t limit = storageBlockLimit();
    ASSERT_GE(limit, std::uint64_t{1} << 24); // GL 4.3's minimum
    try {
        // Refused before glBufferData: nothing of this size is allocated.
        gl::Buffer tooLarge("positions", static_cast<std::size_t>(limit) + 16);
        FAIL() << "a " << limit + 16 << "-byte buffer was allocated";
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_THAT(message, ::testing::HasSubstr("buffer 'positions' needs " + std::to_string(limit + 16) +
                                                  " bytes"));
        EXPECT_THAT(message,
                    ::testing::HasSubstr("GL_MAX_SHADER_STORAGE_BLOCK_SIZE of " + std::to_string(limit)));
    }
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST(BufferLimits, BuffersUpToTheGuaranteedSizeNeedNoQueryAndWork) {
    const std::uint32_t value = 0xC0FFEEu;
    gl::Buffer small("small", sizeof value, &value); // below the 16-byte placeholder: ASan-checked upload
    std::uint32_t back = 0;
    small.download(0, sizeof back, &back);
    EXPECT_EQ(back, value);
    EXPECT_EQ(small.bytes(), sizeof value);
}

} // namespace
} // namespace glcollide
