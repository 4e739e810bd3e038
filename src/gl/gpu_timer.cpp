#include "gl/gpu_timer.hpp"

#include "gl/debug_output.hpp"

#include <epoxy/gl.h>

namespace glcollide::gl {

GpuTimer::GpuTimer(std::size_t sectionCount) : m_sectionCount(sectionCount) {}

void GpuTimer::beginFrame() {
    m_used = 0;
    m_brackets.clear();
}

std::uint32_t GpuTimer::stamp() {
    const bool fresh = m_used == m_queries.size();
    if (fresh) {
        GLuint q = 0;
        glGenQueries(1, &q);
        m_queries.emplace_back(q);
    }
    const std::uint32_t q = m_queries[m_used++].name();
    glQueryCounter(q, GL_TIMESTAMP);
    // glGenQueries only reserves a name; the object exists (and can be labelled) once used.
    if (fresh) labelObject(GL_QUERY, q, "glcollide/timestamp");
    return q;
}

void GpuTimer::begin(std::size_t section) {
    const std::uint32_t q = stamp();
    m_brackets.push_back({section, q, 0});
}

void GpuTimer::end(std::size_t section) {
    const std::uint32_t q = stamp();
    for (auto it = m_brackets.rbegin(); it != m_brackets.rend(); ++it)
        if (it->section == section && it->end == 0) {
            it->end = q;
            return;
        }
}

std::vector<double> GpuTimer::resolveMilliseconds() {
    std::vector<double> ms(m_sectionCount, 0.0);
    for (const Bracket& b : m_brackets) {
        if (b.end == 0) continue;
        GLuint64 t0 = 0, t1 = 0;
        glGetQueryObjectui64v(b.start, GL_QUERY_RESULT, &t0);
        glGetQueryObjectui64v(b.end, GL_QUERY_RESULT, &t1);
        if (t1 > t0) ms[b.section] += static_cast<double>(t1 - t0) * 1e-6;
    }
    return ms;
}

TimedSection::TimedSection(GpuTimer* timer, std::size_t section, std::string_view name)
    : m_group(name), m_timer(timer), m_section(section) {
    if (m_timer) m_timer->begin(m_section);
}

TimedSection::~TimedSection() {
    if (m_timer) m_timer->end(m_section);
}

} // namespace glcollide::gl
