#include "passes/collision/stage_chain.hpp"

#include <algorithm>

namespace glcollide::passes {

std::vector<PassId> StageChain::passes() const {
    std::vector<PassId> p;
    for (const Stage& s : m_stages)
        if (std::find(p.begin(), p.end(), s.pass) == p.end()) p.push_back(s.pass);
    return p;
}

std::vector<std::uint32_t> StageChain::outputsFrom(std::size_t first) const {
    std::vector<std::uint32_t> lists;
    for (std::size_t s = first; s < m_stages.size(); ++s)
        for (std::uint32_t list : m_stages[s].outputs)
            if (std::find(lists.begin(), lists.end(), list) == lists.end()) lists.push_back(list);
    return lists;
}

void StageChain::runFrom(std::size_t first, gl::GpuTimer* timer) const {
    for (std::size_t s = first; s < m_stages.size(); ++s) {
        const gl::TimedSection section(timer, passIndex(m_stages[s].pass), passName(m_stages[s].pass));
        m_stages[s].run();
    }
}

std::uint32_t StageChain::run(AppendLists& lists, gl::GpuTimer* timer) const {
    lists.resetGrowths();
    lists.resetCounts(outputsFrom(0));
    lists.bind();
    runFrom(0, timer);
    // The one sync point of the chain (plus one per rerun).
    std::uint32_t reruns = 0;
    for (lists.readCounters();; lists.readCounters()) {
        std::size_t first = m_stages.size();
        for (std::size_t s = 0; s < m_stages.size() && first == m_stages.size(); ++s) {
            const Stage& stage = m_stages[s];
            const bool overflowed = std::any_of(stage.outputs.begin(), stage.outputs.end(),
                                                [&](std::uint32_t list) { return lists.overflowed(list); });
            // retry() arranges more work when it answers true: ask it only when it decides.
            if (overflowed || (stage.retry && stage.retry())) first = s;
        }
        if (first == m_stages.size()) return reruns;
        for (std::uint32_t list : m_stages[first].outputs)
            if (lists.overflowed(list)) lists.grow(list);
        lists.resetCounts(outputsFrom(first));
        lists.bind();
        runFrom(first, timer);
        ++reruns;
    }
}

} // namespace glcollide::passes
