#include "app/self_check_report.hpp"

#include "engine/robust_self_check.hpp"

#include <iostream>
#include <sstream>

namespace glcollide::app {
namespace {

const char* status(const SelfCheckReport& r) {
    if (r.mode == SelfCheckMode::Off) return "off";
    if (!r.needed) return "not_needed";
    return r.passed ? "passed" : "failed";
}

nlohmann::json orNull(const std::string& text) {
    return text.empty() ? nlohmann::json(nullptr) : nlohmann::json(text);
}

} // namespace

nlohmann::json selfCheckJson(const SelfCheckReport& r) {
    return {{"status", status(r)},        {"mode", engine::toString(r.mode)},
            {"remembered", r.remembered}, {"cases", r.cases},
            {"wrong", r.wrong},           {"first_wrong", orNull(r.firstWrong)},
            {"ms", r.milliseconds},       {"marker", orNull(r.marker)}};
}

std::string selfCheckLine(const SelfCheckReport& r) {
    std::ostringstream out;
    if (r.mode == SelfCheckMode::Off) return "off";
    if (!r.needed) return "not needed (robust precision not used)";
    if (r.passed && r.remembered)
        out << "passed (remembered" << (r.marker.empty() ? " earlier in this process" : " in " + r.marker)
            << ")";
    else if (r.passed)
        out << "passed (" << r.cases << " cases in " << r.milliseconds << " ms)";
    else
        out << "FAILED (" << r.wrong << " of " << r.cases << " cases wrong; first: " << r.firstWrong << ")";
    return out.str();
}

SelfCheckReport checkRobustBeforeUse() {
    const SelfCheckReport report =
        engine::runRobustSelfCheck(engine::effectiveSelfCheckMode(SelfCheckMode::Error));
    if (!report.message.empty()) std::cerr << "glcollide: warning: " << report.message << "\n";
    return report;
}

} // namespace glcollide::app
