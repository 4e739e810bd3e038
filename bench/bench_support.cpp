#include "bench_support.hpp"

#include "benchkit/run_context.hpp"

#include <benchmark/benchmark.h>

#include <cctype>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <exception>
#include <fstream>
#include <iostream>
#include <vector>

namespace glcollide::bench {
std::string rendererSlug(std::string_view renderer) { return benchkit::rendererSlug(renderer); }

bool parseFlags(int argc, char** argv, Flags& flags) {
    for (int i = 1; i < argc; ++i) {
        const std::string_view arg = argv[i];
        if (arg == "--print-renderer-slug")
            flags.printSlug = true;
        else if (arg.rfind("--device=", 0) == 0)
            flags.device = std::string(arg.substr(9));
        else {
            std::cerr << argv[0] << ": unknown argument " << arg
                      << " (own flags: --device=<selector>, --print-renderer-slug; see --help)\n";
            return false;
        }
    }
    return true;
}

void recordContext(const HeadlessContext& context, const std::string& timing) {
    const benchkit::RunContext run = benchkit::describeRun(context);
    benchmark::AddCustomContext("gl_renderer", run.renderer);
    benchmark::AddCustomContext("gl_renderer_slug", run.rendererSlug);
    benchmark::AddCustomContext("gl_version", run.glVersion);
    benchmark::AddCustomContext("gl_vendor", run.glVendor);
    benchmark::AddCustomContext("gl_software_renderer", run.softwareRenderer ? "true" : "false");
    benchmark::AddCustomContext("egl_device", run.eglDevice);
    benchmark::AddCustomContext("egl_vendor", run.eglVendor);
    benchmark::AddCustomContext("egl_version", run.eglVersion);
    benchmark::AddCustomContext("cpu_model", run.cpuModel);
    benchmark::AddCustomContext("git_commit", run.gitCommit);
    benchmark::AddCustomContext("glcollide_build_type", run.buildType);
    // Google Benchmark writes its own local-time "date"; this one is UTC and ISO 8601.
    benchmark::AddCustomContext("date_utc", run.dateUtc);
    benchmark::AddCustomContext("timing", timing);
}

int exitCode(const char* argv0, std::size_t ran, bool failed) {
    if (ran == 0) {
        std::cerr << argv0 << ": no benchmark matched\n";
        return 1;
    }
    return failed ? 1 : 0;
}

int guardedMain(int argc, char** argv, int (*run)(int, char**)) {
    try {
        return run(argc, argv);
    } catch (const std::exception& e) {
        std::cerr << argv[0] << ": " << e.what() << '\n';
        return 1;
    }
}

} // namespace glcollide::bench
