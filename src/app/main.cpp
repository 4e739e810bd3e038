// glcollide — the command-line tool: a thin layer over the engine (docs/design/README.md, "Modules").

#include "app/commands.hpp"

#include <glcollide/error.hpp>

#include <CLI/CLI.hpp>

#include <iostream>

int main(int argc, char** argv) {
    CLI::App cli{"glcollide: collision and mass-spring simulation in OpenGL 4.3 compute shaders"};
    cli.require_subcommand(1);

    glcollide::app::RunOptions run;
    CLI::App* runCmd = cli.add_subcommand(
        "run", "Simulate a scene headless (the built-in default scene when none is given)");
    runCmd->add_option("scene", run.scenePath, "Scene file (JSON, see docs/scene-format.md)");
    runCmd->add_option("--frames", run.frames, "Frames to simulate (default: the scene's /time/frames)");
    runCmd->add_option("--broad-phase", run.broadPhase,
                       "Override the scene's broad phase: octree, masked, all_pairs or bvh");
    runCmd->add_option("--export", run.exportDir, "Write each exported frame's meshes into this folder");
    runCmd->add_option("--every", run.exportEvery, "Export every K-th frame (with --export)")->default_val(1);
    runCmd->add_option("--format", run.exportFormat, "Export format: obj or ply")->default_val("obj");
    runCmd->add_option("--stats", run.statsPath, "Write per-frame statistics (JSON) to this file");
    runCmd->add_option("--device", run.device,
                       "EGL device: auto, software, <index> or cuda:<n> (env GLCOLLIDE_EGL_DEVICE)");
    runCmd->add_flag("--quiet", run.quiet, "No progress on stderr");
    bool noTiming = false;
    runCmd->add_flag("--no-gpu-timing", noTiming, "Do not time passes (no wait for the GPU each frame)");
    bool frameStep = false;
    runCmd->add_flag("--frame-step", frameStep,
                     "Run a small collision-free scene's whole frame in one FrameStep dispatch "
                     "(EngineOptions::frameStep)");

    glcollide::app::InfoOptions info;
    CLI::App* infoCmd =
        cli.add_subcommand("info", "Print the EGL device, GL vendor, renderer, version and compute limits");
    infoCmd->add_option("--device", info.device, "EGL device: auto, software, <index> or cuda:<n>");
    infoCmd->add_flag("--json", info.json, "Print JSON");

    glcollide::app::QueryTriTriOptions tritri;
    CLI::App* queryCmd = cli.add_subcommand("query", "Answer geometric queries on the GPU");
    queryCmd->require_subcommand(1);
    CLI::App* tritriCmd = queryCmd->add_subcommand(
        "tritri",
        "Triangle-triangle intersection for each row of a CSV (18 numbers: a0 a1 a2 b0 b1 b2, xyz each); "
        "prints 1 or 0 per row");
    tritriCmd
        ->add_option("--in", tritri.inPath,
                     "CSV of triangle pairs; blank lines and # comment lines are skipped")
        ->required();
    tritriCmd->add_option("--out", tritri.outPath, "Write the answers here (default: stdout)");
    tritriCmd
        ->add_option("--precision", tritri.precision, "fast (Moeller 1997, float, epsilon) or robust (exact)")
        ->check(CLI::IsMember({"fast", "robust"}))
        ->default_val("robust");
    tritriCmd->add_option("--device", tritri.device,
                          "EGL device: auto, software, <index> or cuda:<n> (env GLCOLLIDE_EGL_DEVICE)");

    glcollide::app::QueryCcdOptions ccd;
    CLI::App* ccdCmd = queryCmd->add_subcommand(
        "ccd",
        "Continuous collision detection for each query of a CSV (the CCD benchmark's layout: 8 rows per "
        "query, 4 points at t = 0 then at t = 1); prints 1 (may come within the minimum separation) or 0 "
        "per query");
    ccdCmd
        ->add_option("--in", ccd.inPath,
                     "CSV of queries: rows x,y,z as 6 integers (numerator,denominator pairs) or 3 decimals, "
                     "optional ground-truth column (ignored); blank lines and # comment lines are skipped")
        ->required();
    ccdCmd->add_option("--kind", ccd.kind, "vf (vertex, triangle) or ee (edge, edge)")
        ->check(CLI::IsMember({"vf", "ee"}))
        ->required();
    ccdCmd->add_option("--out", ccd.outPath,
                       "Write the answers here (default: stdout) and a summary to stdout");
    ccdCmd->add_flag("--toi", ccd.toi, "Append the time of impact (never later than the true one; 1 when 0)");
    ccdCmd
        ->add_option("--min-separation", ccd.minSeparation,
                     "Answer 1 when the primitives may come within this distance (decimal, >= 0)")
        ->default_val("0");
    ccdCmd
        ->add_option("--budget", ccd.budget,
                     "Boxes per query and piece before answering 1 as capped (at most 21844 on llvmpipe)")
        ->capture_default_str();
    ccdCmd
        ->add_option("--rounds", ccd.rounds,
                     "Rounds in which capped queries continue on halves of their time interval (0: none)")
        ->capture_default_str();
    ccdCmd->add_option("--device", ccd.device,
                       "EGL device: auto, software, <index> or cuda:<n> (env GLCOLLIDE_EGL_DEVICE)");

    glcollide::app::BenchOptions bench;
    CLI::App* benchCmd = cli.add_subcommand(
        "bench",
        "Run a benchmark suite: per-pass GPU time and accuracy against ground truth; writes bench.json "
        "(Google Benchmark schema), SVG plots and report.md (docs/benchmarks.md)");
    benchCmd->add_option("--suite", bench.suite, "Suite file (JSON), or the built-in 'default' or 'smoke'")
        ->default_val("default");
    benchCmd
        ->add_option("--out", bench.outDir,
                     "Output folder; {device} becomes the renderer's name (e.g. llvmpipe)")
        ->default_val("glcollide-bench");
    benchCmd->add_option("--only", bench.only, "Run only these experiments (repeatable)");
    benchCmd
        ->add_option("--frames", bench.frames, "Measured frames of every experiment (overrides the suite)")
        ->check(CLI::Range(1, 100000));
    benchCmd->add_option("--device", bench.device,
                         "EGL device: auto, software, <index> or cuda:<n> (env GLCOLLIDE_EGL_DEVICE)");
    benchCmd->add_flag("--quiet", bench.quiet, "No progress on stderr");

    glcollide::app::RenderOptions render;
    CLI::App* renderCmd = cli.add_subcommand(
        "render", "Simulate a scene headless and write PNG snapshots (frame 0, then every K-th): bodies in "
                  "distinct colours, intersecting faces in red, a ground grid");
    renderCmd->add_option("scene", render.scenePath, "Scene file (JSON; an optional /camera sets the view)");
    renderCmd->add_option("--frames", render.frames,
                          "Frames to simulate (default: the scene's /time/frames)");
    renderCmd->add_option("--broad-phase", render.broadPhase,
                          "Override the scene's broad phase: octree, masked, all_pairs or bvh");
    renderCmd->add_option("--every", render.every, "Write every K-th frame")->default_val(10);
    renderCmd->add_option("--size", render.size, "Image size WIDTHxHEIGHT in pixels")->default_val("800x600");
    renderCmd->add_option("--samples", render.samples, "Multisampling samples per pixel (0: none)")
        ->default_val(4);
    renderCmd->add_flag("--flat", render.flat,
                        "Flat shading, one normal per face (default: smooth, per-vertex normals)");
    renderCmd->add_option("--out", render.outDir, "Output folder for frame_NNNNNN.png")
        ->default_val("glcollide-render");
    renderCmd->add_option(
        "--video", render.video,
        "Write an MP4 (H.264, needs ffmpeg) of every K-th frame at 1/(K*dt) fps instead of PNGs");
    renderCmd->add_option("--device", render.device,
                          "EGL device: auto, software, <index> or cuda:<n> (env GLCOLLIDE_EGL_DEVICE)");
    renderCmd->add_flag("--quiet", render.quiet, "No progress on stderr");

    glcollide::app::ViewOptions view;
    CLI::App* viewCmd = cli.add_subcommand(
        "view",
        "Open a window that runs a scene live in its own GL context, with a panel: orbit, pause, step, pull "
        "nodes with the mouse (docs/viewer.md; needs a display)");
    viewCmd->add_option("scene", view.scenePath,
                        "Scene file (JSON; an optional /camera sets the first view)");
    viewCmd->add_option("--broad-phase", view.broadPhase,
                        "Override the broad phase of every scene opened that has collisions: octree, masked, "
                        "all_pairs or bvh");
    viewCmd->add_option("--device", view.device,
                        "auto, or software (Mesa's llvmpipe): the window system makes the context");
    viewCmd->add_option("--size", view.size, "Window size WIDTHxHEIGHT in pixels")->default_val("1280x800");
    viewCmd->add_option("--frames", view.frames,
                        "Show this many frames without a user, then exit (for scripts and tests)");
    viewCmd->add_option("--screenshot", view.screenshot,
                        "With --frames: write the last frame as the window shows it (PNG)");
    viewCmd->add_option("--input", view.input,
                        "Play a script of key presses and mouse drags (docs/viewer.md)");

    try {
        cli.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return cli.exit(e);
    }
    try {
        if (runCmd->parsed()) {
            run.gpuTiming = !noTiming;
            run.frameStep = frameStep;
            return glcollide::app::runCommand(run);
        }
        if (infoCmd->parsed()) return glcollide::app::infoCommand(info);
        if (tritriCmd->parsed()) return glcollide::app::queryTriTriCommand(tritri);
        if (ccdCmd->parsed()) return glcollide::app::queryCcdCommand(ccd);
        if (benchCmd->parsed()) return glcollide::app::benchCommand(bench);
        if (renderCmd->parsed()) return glcollide::app::renderCommand(render);
        if (viewCmd->parsed()) return glcollide::app::viewCommand(view);
    } catch (const glcollide::Error& e) {
        std::cerr << "glcollide: error: " << e.what() << "\n";
        return 1;
    } catch (const std::exception& e) {
        std::cerr << "glcollide: internal error: " << e.what() << "\n";
        return 2;
    }
    return 0;
}
