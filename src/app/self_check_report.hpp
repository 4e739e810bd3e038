#pragma once
// How the CLI shows the on-device self-check of robust precision (engine/robust_self_check.hpp):
// one JSON object for --stats and `info --json`, one line of text for `info`, and the check run
// before a command answers with robust precision.

#include <glcollide/setup_stats.hpp>

#include <nlohmann/json.hpp>

#include <string>

namespace glcollide::app {

/// {"status": "passed" | "failed" | "off" | "not_needed", "mode", "remembered", "cases", "wrong",
///  "first_wrong", "ms", "marker"}.
nlohmann::json selfCheckJson(const SelfCheckReport& report);

/// "passed (930 cases in 812 ms)", "passed (remembered in FILE)", "FAILED: ...", "off".
std::string selfCheckLine(const SelfCheckReport& report);

/// Runs the check for a command about to use robust precision (query, bench): in the mode
/// GLCOLLIDE_SELF_CHECK sets (default error: a disagreement throws Error); a warn-mode
/// disagreement goes to stderr as "glcollide: warning: ...".
SelfCheckReport checkRobustBeforeUse();

} // namespace glcollide::app
