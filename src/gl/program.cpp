#include "gl/program.hpp"

#include "gl/debug_output.hpp"
#include "gl/embedded_shaders.hpp"

#include <glcollide/error.hpp>

#include <epoxy/gl.h>

#include <regex>
#include <sstream>

namespace glcollide::gl {
namespace {

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

std::string shaderSource(std::string_view name, const std::vector<std::string>& defines) {
    const std::string source = findShader(name).source;
    const std::size_t endOfVersion = source.find('\n') + 1;
    std::string defineBlock;
    for (const std::string& d : defines) {
        const std::size_t space = d.find(' ');
        const std::string macro = d.substr(0, space);
        if (macro.empty() || !std::regex_match(macro, std::regex("[A-Za-z_][A-Za-z0-9_]*")))
            throw Error("invalid shader define '" + d + "' for " + std::string(name));
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
            const std::string fileName = file < shader.fileCount ? std::string("shaders/") + shader.files[file]
                                                                 : "<source " + m[1].str() + ">";
            line = fileName + ":" + m[2].str() + line.substr(static_cast<std::size_t>(m.length(0)));
        }
        out << line << "\n";
    }
    return out.str();
}

ComputeProgram::ComputeProgram(std::string_view shaderName, const std::vector<std::string>& defines)
    : m_shaderName(shaderName) {
    build(shaderSource(shaderName, defines),
          [&](const std::string& log) { return mapShaderLog(log, shaderName); });
}

ComputeProgram ComputeProgram::fromSource(std::string label, const std::string& source) {
    ComputeProgram program;
    program.m_shaderName = std::move(label);
    program.build(source, [](const std::string& log) { return log; });
    return program;
}

void ComputeProgram::build(const std::string& source,
                           const std::function<std::string(const std::string&)>& mapLog) {
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
    const GLuint program = glCreateProgram();
    m_handle = Handle<deleteProgram>(program);
    glAttachShader(program, shader);
    glLinkProgram(program);
    glDetachShader(program, shader);
    glDeleteShader(shader);
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) throw Error("linking shader '" + m_shaderName + "' failed:\n" + mapLog(infoLog(program, true)));
    labelObject(GL_PROGRAM, program, "glcollide/" + m_shaderName);
}

void ComputeProgram::use() const { glUseProgram(name()); }

void ComputeProgram::set(const char* uniform, float value) const {
    glProgramUniform1f(name(), glGetUniformLocation(name(), uniform), value);
}
void ComputeProgram::set(const char* uniform, std::uint32_t value) const {
    glProgramUniform1ui(name(), glGetUniformLocation(name(), uniform), value);
}
void ComputeProgram::set(const char* uniform, const glm::dvec3& value) const {
    glProgramUniform3f(name(), glGetUniformLocation(name(), uniform), static_cast<float>(value.x),
                       static_cast<float>(value.y), static_cast<float>(value.z));
}

void ComputeProgram::dispatch1D(std::uint32_t invocations, std::uint32_t groupSize) const {
    if (invocations == 0) return;
    const std::uint32_t groups = (invocations + groupSize - 1) / groupSize;
    // GL 4.3 guarantees 65535 groups per dimension; larger counts use a 2D grid.
    constexpr std::uint32_t kMaxGroups = 65535;
    const std::uint32_t x = groups < kMaxGroups ? groups : kMaxGroups;
    const std::uint32_t y = (groups + x - 1) / x;
    glDispatchCompute(x, y, 1);
}

} // namespace glcollide::gl
