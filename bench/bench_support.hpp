#pragma once
// What every glcollide benchmark program shares: its own command-line flags, the headless
// context, the run metadata recorded in the JSON context (renderer, EGL device, commit, date), the
// smoke-run rule (no matching benchmark is a failure) and main()'s error handling.

#include <glcollide/headless_context.hpp>

#include <cstddef>
#include <string>
#include <string_view>

namespace glcollide::bench {

/// "llvmpipe (LLVM 15.0.6, 256 bits)" -> "llvmpipe"; "NVIDIA H100 80GB HBM3/PCIe/SSE2" ->
/// "nvidia-h100": the file-name stem of bench/results/<slug>-*.json.
std::string rendererSlug(std::string_view renderer);

/// Parses the program's own flags after benchmark::Initialize: --device=<selector> and
/// --print-renderer-slug. Returns false (after a message) on an unknown one.
struct Flags {
    std::string device;
    bool printSlug = false;
};
bool parseFlags(int argc, char** argv, Flags& flags);

/// Records renderer, EGL device, CPU, commit (HEAD of the source tree at run time), build type,
/// UTC date and how times were taken in the benchmark JSON context.
void recordContext(const HeadlessContext& context, const std::string& timing);

/// The exit code after RunSpecifiedBenchmarks: a filter that matched nothing or a failed case
/// must fail a smoke run, not pass silently.
int exitCode(const char* argv0, std::size_t ran, bool failed);

/// main(): runs `run`, turning exceptions into a one-line message and exit code 1.
int guardedMain(int argc, char** argv, int (*run)(int, char**));

} // namespace glcollide::bench
