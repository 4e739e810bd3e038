#include "app/progress.hpp"

#include <cstdio>
#include <unistd.h>

namespace glcollide::app {

Progress::Progress(std::string label, std::uint64_t total, bool enabled)
    : m_label(std::move(label)), m_total(total), m_enabled(enabled), m_tty(isatty(fileno(stderr)) != 0),
      m_start(std::chrono::steady_clock::now()), m_lastDraw(m_start) {}

void Progress::update(std::uint64_t done) {
    if (!m_enabled || m_total == 0) return;
    const auto now = std::chrono::steady_clock::now();
    const double elapsed = std::chrono::duration<double>(now - m_start).count();
    const double rate = elapsed > 0 ? static_cast<double>(done) / elapsed : 0.0;
    const double eta = rate > 0 ? static_cast<double>(m_total - done) / rate : 0.0;
    if (m_tty) {
        if (now - m_lastDraw < std::chrono::milliseconds(100) && done != m_total) return;
        m_lastDraw = now;
        std::fprintf(stderr, "\r%s %llu/%llu frames  %.1f frames/s  ETA %.0f s   ", m_label.c_str(),
                     static_cast<unsigned long long>(done), static_cast<unsigned long long>(m_total), rate,
                     eta);
    } else {
        const int decile = static_cast<int>(10 * done / m_total);
        if (decile == m_lastDecile) return;
        m_lastDecile = decile;
        std::fprintf(stderr, "%s %3d%% (%llu/%llu frames, %.1f frames/s)\n", m_label.c_str(), decile * 10,
                     static_cast<unsigned long long>(done), static_cast<unsigned long long>(m_total), rate);
    }
}

void Progress::finish() {
    if (m_enabled && m_tty) std::fprintf(stderr, "\n");
}

} // namespace glcollide::app
