#include "gl/program.hpp"

#include "gl/debug_output.hpp"
#include "gl/embedded_shaders.hpp"
#include "gl/program_cache.hpp"
#include "gl/setup_stats_sink.hpp"

#include <glcollide/error.hpp>

#include <epoxy/gl.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <regex>
#include <sstream>

namespace glcollide::gl {
namespace {

std::string hex(std::uint32_t value) {
    std::ostringstream out;
    out << std::hex << value;
    return out.str();
}

const embedded::EmbeddedShader& findShader(std::string_view name) {
    for (std::size_t i = 0; i < embedded::kShaderCount; ++i)
        if (name == embedded::kShaders[i].name) return embedded::kShaders[i];
    throw Error("no embedded shader named '" + std::string(name) + "'");
}

std::string infoLog(GLuint object, bool isProgram) {
    GLint length = 0;
    if (isProgram)
        glGetProgramiv(object, GL_INFO_LOG_LENGTH, &length);
    else
        glGetShaderiv(object, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(length > 0 ? length : 1), '\0');
    if (isProgram)
        glGetProgramInfoLog(object, length, nullptr, log.data());
    else
        glGetShaderInfoLog(object, length, nullptr, log.data());
    while (!log.empty() && (log.back() == '\0' || log.back() == '\n')) log.pop_back();
    return log;
}

} // namespace

std::vector<std::string> embeddedShaderNames() {
    std::vector<std::string> names;
    for (std::size_t i = 0; i < embedded::kShaderCount; ++i) names.emplace_back(embedded::kShaders[i].name);
    return names;
}

std::vector<std::string> shaderFeatures(std::string_view name) {
    std::istringstream words(findShader(name).features);
    std::vector<std::string> features;
    for (std::string w; words >> w;) features.push_back(w);
    return features;
}

std::string shaderSource(std::string_view name, const std::vector<std::string>& defines) {
    const embedded::EmbeddedShader& shader = findShader(name);
    const std::string source = shader.source;
    const std::size_t endOfVersion = source.find('\n') + 1;
    std::string defineBlock;
    for (const std::string& d : defines) {
        const std::size_t space = d.find(' ');
        const std::string macro = d.substr(0, space);
        if (macro.empty() || !std::regex_match(macro, std::regex("[A-Za-z_][A-Za-z0-9_]*")))
            throw Error("invalid shader define '" + d + "' for " + std::string(name));
        // GLC_ switches are the shader's declared features: only those variants were validated at
        // build time (tools/shader_embed.cpp). A different kernel belongs in its own file.
        if (macro.rfind("GLC_", 0) == 0 &&
            !std::regex_search(shader.features, std::regex("(^| )" + macro + "( |$)")))
            throw Error("shader '" + std::string(name) + "' has no feature " + macro + " (declared: '" +
                        shader.features + "')");
        defineBlock += "#define " + d + "\n";
    }
    // The embedded text continues with "#line 2 0", so inserted lines do not shift locations.
    return source.substr(0, endOfVersion) + defineBlock + source.substr(endOfVersion);
}

std::string mapShaderLog(const std::string& log, std::string_view shaderName) {
    const embedded::EmbeddedShader& shader = findShader(shaderName);
    static const std::regex mesaRe(R"(^(\d+):(\d+)\(\d+\))");
    static const std::regex nvidiaRe(R"(^(\d+)\((\d+)\))");
    std::istringstream in(log);
    std::ostringstream out;
    std::string line;
    while (std::getline(in, line)) {
        std::smatch m;
        if (std::regex_search(line, m, mesaRe) || std::regex_search(line, m, nvidiaRe)) {
            const std::size_t file = std::stoul(m[1].str());
            const std::string fileName = file < shader.fileCount
                                             ? std::string("shaders/") + shader.files[file]
                                             : "<source " + m[1].str() + ">";
            line = fileName + ":" + m[2].str() + line.substr(static_cast<std::size_t>(m.length(0)));
        }
        out << line << "\n";
    }
    return out.str();
}

ComputeProgram::ComputeProgram(std::string_view shaderName, const std::vector<std::string>& defines)
    : m_shaderName(shaderName) {
    build(shaderSource(shaderName, defines), defines,
          [&](const std::string& log) { return mapShaderLog(log, shaderName); });
}

ComputeProgram ComputeProgram::fromSource(std::string label, const std::string& source) {
    ComputeProgram program;
    program.m_shaderName = std::move(label);
    program.build(source, {}, [](const std::string& log) { return log; });
    return program;
}

void ComputeProgram::build(const std::string& source, const std::vector<std::string>& defines,
                           const std::function<std::string(const std::string&)>& mapLog) {
    const auto start = std::chrono::steady_clock::now();
    ProgramCache cache(cacheLocationFromEnvironment());
    const std::string key = cache.usable() ? programCacheKey(currentDriverIdentity(), source) : std::string();
    bool hit = false;
    if (cache.usable()) {
        m_handle = Handle<deleteProgram>(glCreateProgram());
        hit = cache.load(m_handle.name(), m_shaderName, key);
    }
    if (!hit) {
        // A fresh object: a program that failed glProgramBinary is not reused.
        m_handle = compileAndLink(source, mapLog, cache.usable());
        cache.store(m_handle.name(), m_shaderName, key);
    }
    labelObject(GL_PROGRAM, m_handle.name(), "glcollide/" + m_shaderName);
    readActiveUniforms();
    if (SetupStats* sink = activeSetupStats()) {
        if (sink->cacheFolder.empty() && cache.location().enabled)
            sink->cacheFolder = cache.location().folder.string();
        if (sink->cacheNote.empty()) sink->cacheNote = cache.note();
    }
    recordProgramSetup(
        {m_shaderName, defines, fnv1a64(source),
         std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count(), hit});
}

Handle<deleteProgram>
ComputeProgram::compileAndLink(const std::string& source,
                               const std::function<std::string(const std::string&)>& mapLog,
                               bool retrievable) const {
    const GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
    const char* text = source.c_str();
    glShaderSource(shader, 1, &text, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        const std::string log = mapLog(infoLog(shader, false));
        glDeleteShader(shader);
        throw Error("compiling shader '" + m_shaderName + "' failed:\n" + log);
    }
    Handle<deleteProgram> program(glCreateProgram());
    // Set before linking, so the driver keeps what glGetProgramBinary needs (the cache stores it).
    if (retrievable) glProgramParameteri(program.name(), GL_PROGRAM_BINARY_RETRIEVABLE_HINT, GL_TRUE);
    glAttachShader(program.name(), shader);
    glLinkProgram(program.name());
    glDetachShader(program.name(), shader);
    glDeleteShader(shader);
    glGetProgramiv(program.name(), GL_LINK_STATUS, &ok);
    if (!ok)
        throw Error("linking shader '" + m_shaderName + "' failed:\n" +
                    mapLog(infoLog(program.name(), true)));
    return program;
}

void ComputeProgram::use() const {
    glUseProgram(name());
}

void ComputeProgram::readActiveUniforms() {
    m_uniforms.clear();
    GLint count = 0;
    glGetProgramInterfaceiv(name(), GL_UNIFORM, GL_ACTIVE_RESOURCES, &count);
    const GLenum properties[] = {GL_LOCATION, GL_TYPE, GL_NAME_LENGTH};
    for (GLint i = 0; i < count; ++i) {
        GLint values[3] = {-1, 0, 0};
        glGetProgramResourceiv(name(), GL_UNIFORM, static_cast<GLuint>(i), 3, properties, 3, nullptr, values);
        if (values[0] < 0) continue; // a block member: set through its buffer, not here
        std::string text(static_cast<std::size_t>(std::max(values[2], 1)), '\0');
        glGetProgramResourceName(name(), GL_UNIFORM, static_cast<GLuint>(i), values[2], nullptr, text.data());
        text.resize(std::strlen(text.c_str()));
        m_uniforms.push_back({std::move(text), values[0], static_cast<GLenum>(values[1])});
    }
}

const ComputeProgram::ActiveUniform* ComputeProgram::find(const char* uniform, std::uint32_t type) const {
    for (const ActiveUniform& u : m_uniforms) {
        if (u.name != uniform) continue;
        if (u.type != type)
            throw Error("program '" + m_shaderName + "': uniform " + u.name + " has GL type 0x" +
                        hex(u.type) + ", set with a value of GL type 0x" + hex(type));
        return &u;
    }
    return nullptr;
}

void ComputeProgram::set(const char* uniform, float value) const {
    if (const ActiveUniform* u = find(uniform, GL_FLOAT)) glProgramUniform1f(name(), u->location, value);
}
void ComputeProgram::set(const char* uniform, std::uint32_t value) const {
    if (const ActiveUniform* u = find(uniform, GL_UNSIGNED_INT))
        glProgramUniform1ui(name(), u->location, value);
}
void ComputeProgram::set(const char* uniform, const glm::dvec3& value) const {
    if (const ActiveUniform* u = find(uniform, GL_FLOAT_VEC3))
        glProgramUniform3f(name(), u->location, static_cast<float>(value.x), static_cast<float>(value.y),
                           static_cast<float>(value.z));
}

void ComputeProgram::dispatch1D(std::uint32_t invocations, std::uint32_t groupSize) const {
    if (invocations == 0) return;
    const std::uint32_t groups = (invocations + groupSize - 1) / groupSize;
    // GL 4.3 guarantees 65535 groups per dimension; larger counts use a 2D grid.
    constexpr std::uint32_t kMaxGroups = 65535;
    const std::uint32_t x = groups < kMaxGroups ? groups : kMaxGroups;
    const std::uint32_t y = (groups + x - 1) / x;
    dispatch(x, y, 1);
}

namespace {
std::uint64_t g_dispatches = 0;
}

void ComputeProgram::dispatch(std::uint32_t x, std::uint32_t y, std::uint32_t z) {
    ++g_dispatches;
    glDispatchCompute(x, y, z);
}

void ComputeProgram::dispatchIndirect(std::intptr_t offset) {
    ++g_dispatches;
    glDispatchComputeIndirect(static_cast<GLintptr>(offset));
}

std::uint64_t dispatchCount() {
    return g_dispatches;
}

} // namespace glcollide::gl
