#pragma once
// Where ComputeProgram records what building it cost. An Engine opens a SetupStatsScope around
// its construction; every program built on that thread meanwhile adds to that engine's
// SetupStats. Thread-local and scoped, never process-wide, so two engines (or two threads) never
// mix their numbers; with no scope open, nothing is recorded.

#include <glcollide/setup_stats.hpp>

namespace glcollide::gl {

class SetupStatsScope {
  public:
    /// Makes `sink` the active one on this thread until destruction (then the previous one,
    /// so scopes nest).
    explicit SetupStatsScope(SetupStats* sink);
    ~SetupStatsScope();
    SetupStatsScope(const SetupStatsScope&) = delete;
    SetupStatsScope& operator=(const SetupStatsScope&) = delete;

  private:
    SetupStats* m_previous;
};

/// The innermost open scope's sink on this thread, or nullptr.
SetupStats* activeSetupStats();

/// Adds one program to the active sink, if any.
void recordProgramSetup(ProgramSetup program);

} // namespace glcollide::gl
