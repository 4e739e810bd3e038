#pragma once
// Per-pass GPU time from GL_TIMESTAMP query pairs. Timestamps (not GL_TIME_ELAPSED) because
// elapsed-time queries cannot nest with a host's, and read 0 around compute on Mesa
// (notes/platform.md §2.4).

#include "gl/debug_output.hpp"
#include "gl/handles.hpp"

#include <cstdint>
#include <string_view>
#include <vector>

namespace glcollide::gl {

class GpuTimer {
  public:
    explicit GpuTimer(std::size_t sectionCount);

    /// Starts a frame: forgets the previous frame's queries (their objects are reused).
    void beginFrame();
    /// Brackets one section's work; sections may repeat within a frame (substeps): times add up.
    void begin(std::size_t section);
    void end(std::size_t section);
    /// Waits for this frame's queries and returns milliseconds per section.
    std::vector<double> resolveMilliseconds();

  private:
    /// Writes a GL_TIMESTAMP into the next free query (made and labelled on first use).
    std::uint32_t stamp();

    std::size_t m_sectionCount;
    std::vector<Handle<deleteQuery>> m_queries;
    std::size_t m_used = 0;
    // (section, start query, end query) for each bracket of the current frame
    struct Bracket {
        std::size_t section;
        std::uint32_t start, end;
    };
    std::vector<Bracket> m_brackets;
};

/// The bracket around one pass's dispatches: a debug group named after the pass (RenderDoc,
/// apitrace) and, when `timer` is not null, its timer section.
class TimedSection {
  public:
    TimedSection(GpuTimer* timer, std::size_t section, std::string_view name);
    ~TimedSection();
    TimedSection(const TimedSection&) = delete;
    TimedSection& operator=(const TimedSection&) = delete;

  private:
    DebugGroup m_group;
    GpuTimer* m_timer;
    std::size_t m_section;
};

} // namespace glcollide::gl
