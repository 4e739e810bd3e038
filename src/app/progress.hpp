#pragma once
// Progress of long runs on stderr: a redrawn line on a terminal, otherwise a line every 10 %.

#include <chrono>
#include <cstdint>
#include <string>

namespace glcollide::app {

class Progress {
  public:
    Progress(std::string label, std::uint64_t total, bool enabled);
    void update(std::uint64_t done);
    void finish();

  private:
    std::string m_label;
    std::uint64_t m_total;
    bool m_enabled;
    bool m_tty;
    int m_lastDecile = -1;
    std::chrono::steady_clock::time_point m_start, m_lastDraw;
};

} // namespace glcollide::app
