// glcollide render: headless simulation with PNG snapshots drawn from the engine's own buffers.
#include "app/commands.hpp"
#include "app/video_pipe.hpp"
#include "app/progress.hpp"
#include "render/scene_renderer.hpp"

#include <glcollide/engine.hpp>
#include <glcollide/error.hpp>
#include <glcollide/headless_context.hpp>
#include <glcollide/scene.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <regex>

namespace glcollide::app {
namespace {

std::string frameName(std::uint64_t frame) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%06llu.png", static_cast<unsigned long long>(frame));
    return name;
}

} // namespace

/// "WIDTHxHEIGHT", each 1 ... kMaxSide (the device may allow less: the renderer checks again).
std::pair<int, int> parseSize(const std::string& text, const std::string& option) {
    constexpr int kMaxSide = 16384;
    static const std::regex re(R"(([0-9]{1,6})[xX]([0-9]{1,6}))");
    std::smatch m;
    const std::string expected = option + ": expected WIDTHxHEIGHT in pixels, each 1 ... " +
                                 std::to_string(kMaxSide) + " (e.g. 800x600), got '" + text + "'";
    if (!std::regex_match(text, m, re)) throw Error(expected);
    const int w = std::stoi(m[1].str()), h = std::stoi(m[2].str());
    if (w < 1 || h < 1 || w > kMaxSide || h > kMaxSide) throw Error(expected);
    return {w, h};
}

int renderCommand(const RenderOptions& options) {
    const auto [width, height] = parseSize(options.size);
    if (options.every <= 0) throw Error("--every must be positive");
    if (options.samples < 0) throw Error("--samples must be >= 0");
    Scene scene = options.scenePath.empty() ? defaultScene() : loadScene(options.scenePath);
    if (!options.broadPhase.empty()) overrideBroadPhase(scene, options.broadPhase);
    if (options.frames) {
        if (*options.frames <= 0) throw Error("--frames must be positive");
        scene.time.frames = *options.frames;
    }
    const bool video = !options.video.empty();
    // Checked before the engine starts: a missing ffmpeg is an error, not minutes of simulation lost.
    if (video && findOnPath("ffmpeg").empty())
        throw Error(
            "--video needs the ffmpeg program, which is not on PATH (Debian: apt-get install ffmpeg)");
    if (!video) {
        std::error_code ec;
        std::filesystem::create_directories(options.outDir, ec);
        if (ec) throw Error(options.outDir + ": cannot create output directory: " + ec.message());
    }

    HeadlessContext context({options.device});
    Engine engine(scene, {false});
    for (const std::string& w : engine.warnings()) std::cerr << "glcollide: warning: " << w << "\n";
    render::SceneRenderer renderer(engine, {width, height, options.samples, !options.flat});
    const bool collisions =
        engine.scene().effects.has(Effect::Collisions) || engine.scene().effects.has(Effect::SelfCollisions);
    const auto frames = static_cast<std::uint64_t>(scene.time.frames);
    std::cout << "scene: " << engine.scene().name << "\n"
              << "device: " << context.deviceDescription() << " | " << context.glInfo().renderer << "\n"
              << "images: " << width << "x" << height << ", " << (renderer.samples() ? renderer.samples() : 1)
              << " sample(s) per pixel, frame 0 and every " << options.every << " of " << frames
              << " frames\n";

    std::size_t written = 0, maxHighlighted = 0;
    std::optional<VideoPipe> pipe;
    if (video) pipe.emplace(options.video, width, height, 1.0 / (options.every * engine.scene().time.dt));
    auto snapshot = [&](std::uint64_t frame) {
        // Highlights for exactly the drawn state (the last substep's pairs describe the positions
        // before its NodeUpdate; frame 0 has had no substep at all).
        if (collisions) engine.detectCollisions();
        const render::Image image = renderer.renderFrame(engine);
        maxHighlighted = std::max(maxHighlighted, renderer.highlightedFaces());
        if (pipe)
            pipe->write(image.rgba);
        else
            render::writePng(std::filesystem::path(options.outDir) / frameName(frame), image);
        ++written;
    };
    snapshot(0);
    Progress progress("glcollide render", frames, !options.quiet);
    for (std::uint64_t f = 1; f <= frames; ++f) {
        engine.step();
        if (f % static_cast<std::uint64_t>(options.every) == 0) snapshot(f);
        progress.update(f);
    }
    progress.finish();
    if (pipe) pipe->finish();
    std::cout << "wrote " << written
              << (pipe ? " frames to " + options.video : " PNG frames to " + options.outDir);
    if (collisions) std::cout << " (at most " << maxHighlighted << " faces highlighted as intersecting)";
    std::cout << "\n";
    return 0;
}

} // namespace glcollide::app
