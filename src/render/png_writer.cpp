// PNG output through stb_image_write (Debian libstb-dev); its implementation is compiled here only.
#include "render/scene_renderer.hpp"

#include <glcollide/error.hpp>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STBI_WRITE_NO_STDIO
#include <stb/stb_image_write.h>

#include <fstream>

namespace glcollide::render {
namespace {

void appendBytes(void* context, void* data, int size) {
    auto* out = static_cast<std::vector<unsigned char>*>(context);
    const auto* bytes = static_cast<const unsigned char*>(data);
    out->insert(out->end(), bytes, bytes + size);
}

} // namespace

void writePng(const std::filesystem::path& path, const Image& image) {
    if (image.width <= 0 || image.height <= 0 ||
        image.rgba.size() !=
            static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 4)
        throw Error(path.string() + ": cannot write an empty or malformed image");
    std::vector<unsigned char> rgb(static_cast<std::size_t>(image.width) *
                                   static_cast<std::size_t>(image.height) * 3);
    for (std::size_t i = 0, n = rgb.size() / 3; i < n; ++i)
        for (std::size_t c = 0; c < 3; ++c) rgb[3 * i + c] = image.rgba[4 * i + c];
    std::vector<unsigned char> png;
    if (stbi_write_png_to_func(appendBytes, &png, image.width, image.height, 3, rgb.data(),
                               image.width * 3) == 0)
        throw Error(path.string() + ": PNG encoding failed");
    std::ofstream out(path, std::ios::binary);
    if (!out) throw Error(path.string() + ": cannot open for writing");
    out.write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
    if (!out) throw Error(path.string() + ": write failed");
}

} // namespace glcollide::render
