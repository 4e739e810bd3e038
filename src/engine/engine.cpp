#include <glcollide/engine.hpp>

#include "cpu/dynamics_twin.hpp"
#include "cpu/flat_model.hpp"
#include "cpu/stability.hpp"
#include "engine/pipeline_plan.hpp"
#include "gl/debug_output.hpp"
#include "gl/gpu_timer.hpp"
#include "gl/layout.hpp"
#include "passes/dynamics_passes.hpp"

#include <glcollide/error.hpp>
#include <glcollide/gl_info.hpp>

#include <epoxy/gl.h>
#include <glm/vec4.hpp>

#include <chrono>
#include <cmath>
#include <optional>
#include <sstream>

namespace glcollide {
namespace {

template <typename T>
gl::Buffer makeBuffer(const char* label, const std::vector<T>& data) {
    return gl::Buffer(label, data.size() * sizeof(T), data.empty() ? nullptr : data.data());
}

std::vector<glm::vec4> packNodes(const std::vector<glm::dvec3>& xyz, const std::vector<double>* w) {
    std::vector<glm::vec4> out(xyz.size());
    for (std::size_t i = 0; i < xyz.size(); ++i)
        out[i] = glm::vec4(glm::vec3(xyz[i]), w ? static_cast<float>((*w)[i]) : 0.0f);
    return out;
}

std::vector<glm::dvec3> unpackNodes(const gl::Buffer& buffer, std::uint32_t count) {
    std::vector<glm::vec4> raw(count);
    buffer.download(0, raw.size() * sizeof(glm::vec4), raw.data());
    std::vector<glm::dvec3> out(count);
    for (std::size_t i = 0; i < count; ++i) out[i] = glm::dvec3(glm::vec3(raw[i]));
    return out;
}

} // namespace

struct Engine::Impl {
    Scene scene;
    EngineOptions options;
    cpu::FlatModel model;
    engine::PipelinePlan plan;
    SubstepInfo substeps;
    std::vector<std::string> warnings;
    passes::DeviceBuffers buffers;
    std::optional<passes::NodeForcePass> nodeForce;
    std::optional<passes::SpringUpdatePass> springUpdate;
    std::optional<passes::NodeUpdatePass> nodeUpdate;
    std::vector<std::string> passNames;
    gl::GpuTimer timer{3};
    StepStats stats;

    void chooseSubsteps();
    void allocate();
    template <typename Pass, typename... Args>
    void run(std::size_t section, const Pass& pass, Args&&... args);
};

void Engine::Impl::chooseSubsteps() {
    const double dt = scene.time.dt;
    const cpu::StabilityLimit limit =
        cpu::stableSubstep(model, plan.springUpdate, plan.nodeForceParams);
    const int stable = cpu::substepsFor(dt, limit);
    substeps.stableSubsteps = stable;
    substeps.maxStableSubstep = limit.maxSubstep;
    substeps.limitingNode = limit.node;
    substeps.automatic = scene.time.substeps == 0;
    if (substeps.automatic) {
        if (stable > cpu::kMaxSubsteps) {
            std::ostringstream msg;
            msg << scene.sourcePath.string() << ": scene too stiff: explicit integration needs "
                << "substeps of at most " << limit.maxSubstep << " s (node " << limit.node
                << ": omega " << limit.omega << " 1/s), more than " << cpu::kMaxSubsteps
                << " per frame of " << dt << " s; lower the stiffness, raise the masses or "
                << "lower /time/dt";
            throw Error(msg.str());
        }
        substeps.substeps = stable;
    } else {
        substeps.substeps = scene.time.substeps;
        if (substeps.substeps < stable)
            warnings.push_back("/time/substeps " + std::to_string(substeps.substeps) +
                               " is below the stability limit of " + std::to_string(stable) +
                               " substeps per frame: the simulation may blow up");
    }
    substeps.substepLength = dt / substeps.substeps;
    plan.nodeUpdateParams.h = substeps.substepLength;
}

void Engine::Impl::allocate() {
    const cpu::FlatModel& m = model;
    buffers.nodeCount = static_cast<std::uint32_t>(m.nodeCount());
    buffers.faceCount = static_cast<std::uint32_t>(m.faceCount());
    buffers.springCount = static_cast<std::uint32_t>(m.springs.size());
    if (!plan.nodeUpdate) return;
    buffers.positions = makeBuffer("positions", packNodes(m.positions, &m.inverseMasses));
    buffers.velocities = makeBuffer("velocities", packNodes(m.velocities, nullptr));
    buffers.faces = makeBuffer("faces", m.faceIndices);
    if (plan.nodeForce || plan.springUpdate)
        buffers.forces = gl::Buffer("forces", m.nodeCount() * sizeof(glm::vec4));
    if (plan.springUpdate) {
        std::vector<gpu::GpuSpring> springs;
        springs.reserve(m.springs.size());
        for (const cpu::FlatSpring& s : m.springs)
            springs.push_back({s.a, s.b, static_cast<float>(s.restLength),
                               static_cast<float>(s.stiffness), static_cast<float>(s.damping), 0u, 0u, 0u});
        for (std::size_t o = 0; o < m.objects.size(); ++o)
            for (std::uint32_t k = 0; k < m.objects[o].springCount; ++k)
                springs[m.objects[o].firstSpring + k].object = static_cast<std::uint32_t>(o);
        buffers.springs = makeBuffer("springs", springs);
        buffers.nodeSpringOffsets = makeBuffer("nodeSpringOffsets", m.nodeSprings.offsets);
        buffers.nodeSpringList = makeBuffer("nodeSpringList", m.nodeSprings.items);
    }
    if (plan.nodeForce && plan.nodeForceParams.wind) {
        buffers.nodeFaceOffsets = makeBuffer("nodeFaceOffsets", m.nodeFaces.offsets);
        buffers.nodeFaceList = makeBuffer("nodeFaceList", m.nodeFaces.items);
    }
}

template <typename Pass, typename... Args>
void Engine::Impl::run(std::size_t section, const Pass& pass, Args&&... args) {
    gl::DebugGroup group(Pass::kName);
    if (options.gpuTiming) timer.begin(section);
    pass.dispatch(buffers, std::forward<Args>(args)...);
    if (options.gpuTiming) timer.end(section);
}

Engine::Engine(const Scene& scene, const EngineOptions& options) : m_impl(std::make_unique<Impl>()) {
    Impl& d = *m_impl;
    validateScene(scene);
    requireGl43();
    d.scene = scene;
    d.options = options;
    d.plan = engine::planPipeline(scene);
    d.model = cpu::flatten(scene);
    d.chooseSubsteps();
    d.allocate();
    if (d.plan.nodeForce) d.nodeForce.emplace(d.plan.nodeForceParams);
    if (d.plan.springUpdate) d.springUpdate.emplace(d.plan.springUpdateParams);
    if (d.plan.nodeUpdate) d.nodeUpdate.emplace(d.plan.nodeUpdateParams);
    d.passNames = d.plan.passes();
    d.stats.substeps = d.substeps.substeps;
    for (const std::string& name : d.passNames) d.stats.passes.push_back({name, 0.0});
}

Engine::~Engine() = default;
Engine::Engine(Engine&&) noexcept = default;
Engine& Engine::operator=(Engine&&) noexcept = default;

void Engine::step() {
    Impl& d = *m_impl;
    const auto start = std::chrono::steady_clock::now();
    if (d.options.gpuTiming) d.timer.beginFrame();
    {
        gl::DebugGroup frame("glcollide::Engine::step");
        for (int s = 0; s < d.substeps.substeps; ++s) {
            if (d.nodeForce) d.run(0, *d.nodeForce, d.plan.nodeForceParams);
            if (d.springUpdate) d.run(1, *d.springUpdate);
            if (d.nodeUpdate) d.run(2, *d.nodeUpdate, d.plan.nodeUpdateParams);
        }
    }
    // A host draws positions as vertices and faces as indices right after step().
    glMemoryBarrier(GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_ELEMENT_ARRAY_BARRIER_BIT |
                    GL_SHADER_STORAGE_BARRIER_BIT);
    d.stats.frame += 1;
    d.stats.time = static_cast<double>(d.stats.frame) * d.scene.time.dt;
    if (d.options.gpuTiming) {
        const std::vector<double> ms = d.timer.resolveMilliseconds();
        std::size_t k = 0;
        if (d.nodeForce) d.stats.passes[k++].gpuMilliseconds = ms[0];
        if (d.springUpdate) d.stats.passes[k++].gpuMilliseconds = ms[1];
        if (d.nodeUpdate) d.stats.passes[k++].gpuMilliseconds = ms[2];
    }
    d.stats.wallMilliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

const StepStats& Engine::lastStep() const { return m_impl->stats; }
std::vector<std::string> Engine::pipeline() const { return m_impl->passNames; }
std::vector<std::string> Engine::allocatedBuffers() const { return m_impl->buffers.allocatedLabels(); }
std::size_t Engine::allocatedBytes() const { return m_impl->buffers.allocatedBytes(); }
const SubstepInfo& Engine::substepInfo() const { return m_impl->substeps; }
const std::vector<std::string>& Engine::warnings() const { return m_impl->warnings; }
const Scene& Engine::scene() const { return m_impl->scene; }
std::uint32_t Engine::nodeCount() const { return m_impl->buffers.nodeCount; }
std::uint32_t Engine::faceCount() const { return m_impl->buffers.faceCount; }
std::uint32_t Engine::springCount() const { return m_impl->buffers.springCount; }

std::vector<std::uint32_t> Engine::bodyFirstNodes() const {
    std::vector<std::uint32_t> first;
    for (const cpu::ObjectRange& o : m_impl->model.objects) first.push_back(o.firstNode);
    return first;
}

std::vector<glm::dvec3> Engine::readPositions() const {
    if (!m_impl->buffers.positions) return m_impl->model.positions;
    return unpackNodes(m_impl->buffers.positions, nodeCount());
}

std::vector<glm::dvec3> Engine::readVelocities() const {
    if (!m_impl->buffers.velocities) return m_impl->model.velocities;
    return unpackNodes(m_impl->buffers.velocities, nodeCount());
}

EnergyReport Engine::energy() const {
    const Impl& d = *m_impl;
    const bool gravity = d.scene.effects.has(Effect::Gravity);
    const cpu::Energy e = cpu::energy(readPositions(), readVelocities(), d.model.masses,
                                      d.model.inverseMasses, gravity ? &d.scene.gravity : nullptr,
                                      d.plan.springUpdate ? &d.model.springs : nullptr);
    return {e.kinetic, e.gravitational + e.elastic};
}

std::uint32_t Engine::positionBuffer() const { return m_impl->buffers.positions.name(); }
std::uint32_t Engine::faceIndexBuffer() const { return m_impl->buffers.faces.name(); }

} // namespace glcollide
