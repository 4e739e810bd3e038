// Simulates the built-in scene on a headless GL context with an installed glcollide: the smallest
// complete program. Exit status 0 when every position stays finite.
#include <glcollide/engine.hpp>           // Engine: the scene's state on the GPU and its passes
#include <glcollide/error.hpp>            // Error: what setup failures throw
#include <glcollide/headless_context.hpp> // HeadlessContext: EGL context (embedders use their own)
#include <glcollide/scene.hpp>            // Scene, defaultScene(), loadScene()

#include <cmath>
#include <cstdio>
#include <exception>

int main() {
    try {
        // A GL 4.3 core context, current on this thread: a GPU if EGL offers one, else llvmpipe.
        glcollide::HeadlessContext context;
        std::printf("renderer: %s\n", context.glInfo().renderer.c_str());

        // A cloth pinned at two corners; glcollide::loadScene("file.json") reads one from disk.
        const glcollide::Scene scene = glcollide::defaultScene();
        glcollide::Engine engine(scene); // validates, composes the passes, uploads the buffers

        for (int frame = 0; frame < 5; ++frame) engine.step(); // each frame advances scene.time.dt

        // readPositions() waits for the GPU; a renderer would draw engine.positionBuffer() instead.
        const auto positions = engine.readPositions();
        for (const auto& p : positions) {
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
                std::fprintf(stderr, "non-finite position after %llu frames\n",
                             static_cast<unsigned long long>(engine.lastStep().frame));
                return 1;
            }
        }
        std::printf("%zu nodes finite after %llu frames\n", positions.size(),
                    static_cast<unsigned long long>(engine.lastStep().frame));
        return positions.empty() ? 1 : 0;
    } catch (const glcollide::Error& e) { // no EGL, GL < 4.3, bad scene, shader error ...
        std::fprintf(stderr, "glcollide: %s\n", e.what());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
    }
    return 1;
}
