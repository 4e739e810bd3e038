#include "benchkit/run_context.hpp"

#include <glcollide/headless_context.hpp>

#include <cctype>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <vector>

namespace glcollide::benchkit {
namespace {
std::string runCommand(const std::string& command) {
    std::string out;
    if (FILE* pipe = popen(command.c_str(), "r")) {
        char buf[256];
        while (std::fgets(buf, sizeof buf, pipe)) out += buf;
        if (pclose(pipe) != 0) return {};
    }
    while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
    return out;
}

/// HEAD of the source tree at run time ("-dirty" when tracked files differ from it), so a result
/// names the code it measured even without a re-configure; the configure-time value otherwise.
std::string gitCommit() {
    const std::string dir = GLCOLLIDE_SOURCE_DIR;
    const std::string git = "git -C '" + dir + "' ";
    const std::string head = runCommand(git + "rev-parse --short HEAD 2>/dev/null");
    if (head.empty()) return std::string(GLCOLLIDE_CONFIGURE_COMMIT) + " (configure time)";
    const std::string dirty = runCommand(git + "status --porcelain --untracked-files=no 2>/dev/null");
    return dirty.empty() ? head : head + "-dirty";
}

std::string cpuModel() {
    std::ifstream in("/proc/cpuinfo");
    for (std::string line; std::getline(in, line);)
        if (line.rfind("model name", 0) == 0) {
            const std::size_t colon = line.find(':');
            if (colon != std::string::npos) return line.substr(line.find_first_not_of(" \t", colon + 1));
        }
    return "unknown";
}

std::string utcNow() {
    const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
    std::tm tm{};
    gmtime_r(&now, &tm);
    char buf[32];
    std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
    return buf;
}

} // namespace

/// "llvmpipe (LLVM 15.0.6, 256 bits)" -> "llvmpipe"; "NVIDIA H100 80GB HBM3/PCIe/SSE2" ->
/// "nvidia-h100". Drops "(...)" groups (LLVM version, "(R)") and everything from the first '/'
/// (NVIDIA's bus/ISA suffix), lower-cases, joins words with '-', and stops at the first
/// memory-size word ("80gb") so memory variants of one board share a file name.
std::string rendererSlug(std::string_view renderer) {
    std::vector<std::string> words(1);
    int depth = 0;
    for (char ch : renderer) {
        const auto u = static_cast<unsigned char>(ch);
        if (ch == '(') ++depth;
        if (ch == ')' && depth > 0) {
            --depth;
            continue;
        }
        if (depth > 0) continue;
        if (ch == '/') break;
        if (std::isalnum(u))
            words.back() += static_cast<char>(std::tolower(u));
        else if (!words.back().empty())
            words.emplace_back();
    }
    std::string slug;
    for (const std::string& w : words) {
        if (w.empty()) continue;
        const std::size_t digits = w.find_first_not_of("0123456789");
        const bool memorySize = digits != 0 && digits != std::string::npos &&
                                (w.substr(digits) == "gb" || w.substr(digits) == "mb");
        if (memorySize && !slug.empty()) break;
        if (!slug.empty()) slug += '-';
        slug += w;
    }
    return slug.empty() ? "unknown" : slug;
}

RunContext describeRun(const HeadlessContext& context) {
    const GlInfo& gl = context.glInfo();
    RunContext r;
    r.renderer = gl.renderer;
    r.rendererSlug = rendererSlug(gl.renderer);
    r.glVersion = gl.version;
    r.glVendor = gl.vendor;
    r.softwareRenderer = gl.isSoftware;
    r.eglDevice = context.deviceDescription();
    r.eglVendor = context.eglVendor();
    r.eglVersion = context.eglVersion();
    r.cpuModel = cpuModel();
    r.gitCommit = gitCommit();
    const std::string buildType = GLCOLLIDE_BUILD_TYPE;
    r.buildType = buildType.empty() ? "unspecified" : buildType;
    r.dateUtc = utcNow();
    return r;
}

} // namespace glcollide::benchkit
