#include "gl/setup_stats_sink.hpp"

#include <utility>

namespace glcollide::gl {
namespace {
thread_local SetupStats* t_active = nullptr;
} // namespace

SetupStatsScope::SetupStatsScope(SetupStats* sink) : m_previous(t_active) {
    t_active = sink;
}
SetupStatsScope::~SetupStatsScope() {
    t_active = m_previous;
}

SetupStats* activeSetupStats() {
    return t_active;
}

void recordProgramSetup(ProgramSetup program) {
    SetupStats* sink = t_active;
    if (sink == nullptr) return;
    sink->compileLinkMilliseconds += program.milliseconds;
    (program.cacheHit ? sink->cacheHits : sink->cacheMisses) += 1;
    sink->programs.push_back(std::move(program));
}

} // namespace glcollide::gl
