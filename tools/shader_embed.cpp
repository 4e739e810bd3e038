// Build-time tool: expands `#include "..."` in GLSL compute shaders, inserts `#line` markers with a
// file-number table (so compile errors map back to the real file and line), writes each expanded
// shader to a folder (for glslangValidator) and all of them into one C++ source file, so an
// installed library never searches for shader files at run time.
//
// One kernel per file: a shader may vary only by the feature switches it declares on a line
// `// glcollide-features: GLC_A GLC_B` (effects a scene turns on, e.g. gravity). Every combination
// of them is written out as <stem>.<mask>.comp so glslangValidator checks each variant the engine
// can compile, and a `#if` on any other undeclared GLC_ name fails the build (no hidden variants).
//
// usage: shader_embed OUT_CPP OUT_DIR SHADER_ROOT SHADER.comp...
//   SHADER paths are relative to SHADER_ROOT; includes resolve relative to SHADER_ROOT.

#include <filesystem>
#include <fstream>
#include <iostream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

struct Expansion {
    std::string text;
    std::vector<std::string> files; // index = GLSL source-string number used in #line
};

[[noreturn]] void fail(const std::string& message) {
    std::cerr << "shader_embed: " << message << "\n";
    std::exit(1);
}

std::vector<std::string> readLines(const fs::path& path) {
    std::ifstream in(path);
    if (!in) fail("cannot open " + path.string());
    std::vector<std::string> lines;
    std::string line;
    while (std::getline(in, line)) lines.push_back(line);
    return lines;
}

void expandInto(const fs::path& root, const std::string& name, Expansion& out,
                std::set<std::string>& included, bool isMain) {
    static const std::regex includeRe(R"(^\s*#\s*include\s+"([^"]+)\"\s*(//.*)?$)");
    const int fileNumber = static_cast<int>(out.files.size());
    out.files.push_back(name);
    const std::vector<std::string> lines = readLines(root / name);
    std::size_t first = 0;
    if (isMain) {
        if (lines.empty() || lines[0].rfind("#version", 0) != 0)
            fail(name + ":1: a shader must start with #version");
        out.text += lines[0] + "\n";
        first = 1;
    }
    out.text += "#line " + std::to_string(first + 1) + " " + std::to_string(fileNumber) + "\n";
    for (std::size_t i = first; i < lines.size(); ++i) {
        std::smatch m;
        if (std::regex_match(lines[i], m, includeRe)) {
            const std::string child = m[1].str();
            if (!fs::exists(root / child))
                fail(name + ":" + std::to_string(i + 1) + ": included file not found: " + child);
            if (included.insert(child).second) expandInto(root, child, out, included, false);
            out.text += "#line " + std::to_string(i + 2) + " " + std::to_string(fileNumber) + "\n";
        } else {
            out.text += lines[i] + "\n";
        }
    }
}

std::string stemOf(const std::string& name) {
    return fs::path(name).stem().string();
}

/// The switches named on the main file's `// glcollide-features:` line.
std::vector<std::string> declaredFeatures(const fs::path& root, const std::string& name) {
    static const std::regex featuresRe(R"(^\s*//\s*glcollide-features:(.*)$)");
    std::vector<std::string> features;
    for (const std::string& line : readLines(root / name)) {
        std::smatch m;
        if (!std::regex_match(line, m, featuresRe)) continue;
        std::istringstream words(m[1].str());
        for (std::string w; words >> w;) features.push_back(w);
    }
    return features;
}

/// Fails when the expanded text tests a GLC_ macro that it neither defines nor declares.
void checkNoHiddenVariants(const std::string& name, const std::string& text,
                           const std::vector<std::string>& features) {
    static const std::regex defineRe(R"(#\s*define\s+(GLC_\w+))");
    static const std::regex testRe(
        R"(#\s*(?:ifdef|ifndef|if\s+defined\s*\(?|elif\s+defined\s*\(?)\s*(GLC_\w+))");
    std::set<std::string> known(features.begin(), features.end());
    for (std::sregex_iterator it(text.begin(), text.end(), defineRe), end; it != end; ++it)
        known.insert((*it)[1].str());
    for (std::sregex_iterator it(text.begin(), text.end(), testRe), end; it != end; ++it)
        if (!known.count((*it)[1].str()))
            fail(name + ": tests " + (*it)[1].str() +
                 ", which is not a declared feature (// glcollide-features:); "
                 "put a different kernel in its own file");
}

/// The source with `features` (bit k of mask = features[k]) defined right after #version.
std::string withFeatures(const std::string& text, const std::vector<std::string>& features, unsigned mask) {
    const std::size_t afterVersion = text.find('\n') + 1;
    std::string defines;
    for (std::size_t k = 0; k < features.size(); ++k)
        if (mask & (1u << k)) defines += "#define " + features[k] + "\n";
    return text.substr(0, afterVersion) + defines + text.substr(afterVersion);
}

} // namespace

int main(int argc, char** argv) {
    if (argc < 5) fail("usage: shader_embed OUT_CPP OUT_DIR SHADER_ROOT SHADER.comp...");
    const fs::path outCpp = argv[1];
    const fs::path outDir = argv[2];
    const fs::path root = argv[3];
    fs::create_directories(outDir);
    // Only this run's variants are validated: clear what earlier runs wrote.
    for (const auto& entry : fs::directory_iterator(outDir))
        if (entry.path().extension() == ".comp") fs::remove(entry.path());

    std::ostringstream cpp;
    cpp << "// Generated by tools/shader_embed.cpp from shaders/. Do not edit.\n"
        << "#include \"gl/embedded_shaders.hpp\"\n\n"
        << "namespace glcollide::gl::embedded {\nnamespace {\n";
    std::vector<std::string> entries;
    for (int i = 4; i < argc; ++i) {
        const std::string name = argv[i];
        Expansion expansion;
        std::set<std::string> included;
        expandInto(root, name, expansion, included, true);
        if (expansion.text.find(")glsl\"") != std::string::npos) fail(name + ": contains )glsl\"");
        const std::vector<std::string> features = declaredFeatures(root, name);
        if (features.size() > 6) fail(name + ": more than 6 features (64 variants to validate)");
        checkNoHiddenVariants(name, expansion.text, features);
        // Every variant, for glslangValidator (mask 0: no feature).
        for (unsigned mask = 0; mask < (1u << features.size()); ++mask)
            std::ofstream(outDir / (stemOf(name) + "." + std::to_string(mask) + ".comp"))
                << withFeatures(expansion.text, features, mask);
        std::string featureList;
        for (const auto& f : features) featureList += (featureList.empty() ? "" : " ") + f;
        const std::string id = std::to_string(i - 4);
        cpp << "const char* const kFiles" << id << "[] = {";
        for (const auto& f : expansion.files) cpp << "\"" << f << "\", ";
        cpp << "};\nconst char kSource" << id << "[] = R\"glsl(" << expansion.text << ")glsl\";\n";
        entries.push_back("{\"" + stemOf(name) + "\", kSource" + id + ", kFiles" + id + ", " +
                          std::to_string(expansion.files.size()) + ", \"" + featureList + "\"}");
    }
    cpp << "} // namespace\n\nconst EmbeddedShader kShaders[] = {\n";
    for (const auto& e : entries) cpp << "    " << e << ",\n";
    cpp << "};\nconst std::size_t kShaderCount = " << entries.size() << ";\n\n"
        << "} // namespace glcollide::gl::embedded\n";

    const std::string text = cpp.str();
    std::ifstream existing(outCpp);
    std::stringstream old;
    old << existing.rdbuf();
    if (old.str() != text) std::ofstream(outCpp) << text; // keep the timestamp when unchanged
    return 0;
}
