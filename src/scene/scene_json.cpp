// JSON scene reader: loadScene, parseScene, defaultScene. Format: docs/scene-format.md.
#include "scene/json_errors.hpp"
#include "scene/scene_detail.hpp"

#include <glcollide/error.hpp>
#include <glcollide/scene.hpp>

#include <nlohmann/json.hpp>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

namespace glcollide {
namespace {

using json = nlohmann::json;
using Ptr = json::json_pointer;

/// Where the text came from, so every error can name the file and the JSON pointer.
struct Ctx {
    std::string source;
    std::filesystem::path baseDir;

    [[noreturn]] void fail(const Ptr& p, const std::string& message) const {
        const std::string where = p.empty() ? std::string("(root)") : p.to_string();
        throw Error(source + ": " + where + ": " + message);
    }
};

std::string shown(const json& j) {
    std::string s = j.dump();
    if (s.size() > 60) s = s.substr(0, 57) + "...";
    return s;
}

std::string joinKeys(std::initializer_list<const char*> keys) {
    std::string out;
    for (const char* k : keys) out += (out.empty() ? "" : ", ") + std::string(k);
    return out;
}

void checkObject(const Ctx& c, const json& j, const Ptr& p, std::initializer_list<const char*> allowed) {
    if (!j.is_object()) c.fail(p, "expected an object, got " + shown(j));
    for (const auto& item : j.items()) {
        const bool known =
            std::any_of(allowed.begin(), allowed.end(), [&](const char* k) { return item.key() == k; });
        if (!known)
            c.fail(p / item.key(),
                   "unknown key '" + item.key() + "'; allowed keys here: " + joinKeys(allowed));
    }
}

const json* find(const json& obj, const char* key) {
    auto it = obj.find(key);
    return it == obj.end() ? nullptr : &*it;
}

const json& require(const Ctx& c, const json& obj, const Ptr& p, const char* key) {
    const json* j = find(obj, key);
    if (j == nullptr) c.fail(p / key, "required key is missing");
    return *j;
}

double number(const Ctx& c, const json& j, const Ptr& p, const char* expected = "a number") {
    if (!j.is_number()) c.fail(p, std::string("expected ") + expected + ", got " + shown(j));
    const double v = j.get<double>();
    if (!std::isfinite(v)) c.fail(p, std::string("expected ") + expected + ", got " + shown(j));
    return v;
}

double positive(const Ctx& c, const json& j, const Ptr& p) {
    const double v = number(c, j, p, "a positive number");
    if (!(v > 0.0)) c.fail(p, "expected a positive number, got " + shown(j));
    return v;
}

double nonNegative(const Ctx& c, const json& j, const Ptr& p) {
    const double v = number(c, j, p, "a number >= 0");
    if (!(v >= 0.0)) c.fail(p, "expected a number >= 0, got " + shown(j));
    return v;
}

int integer(const Ctx& c, const json& j, const Ptr& p, long long min, long long max) {
    const std::string expected = "an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "]";
    if (!j.is_number_integer()) c.fail(p, "expected " + expected + ", got " + shown(j));
    // Unsigned JSON integers above INT64_MAX would wrap in get<long long>(): reject them first.
    if (j.is_number_unsigned() && j.get<std::uint64_t>() > static_cast<std::uint64_t>(max))
        c.fail(p, "expected " + expected + ", got " + shown(j));
    const long long v = j.get<long long>();
    if (v < min || v > max) c.fail(p, "expected " + expected + ", got " + shown(j));
    return static_cast<int>(v);
}

std::vector<double> numbers(const Ctx& c, const json& j, const Ptr& p, std::size_t n) {
    if (!j.is_array() || j.size() != n)
        c.fail(p, "expected an array of " + std::to_string(n) + " numbers, got " + shown(j));
    std::vector<double> out;
    for (std::size_t i = 0; i < n; ++i) out.push_back(number(c, j[i], p / i));
    return out;
}

glm::dvec3 vec3(const Ctx& c, const json& j, const Ptr& p) {
    const auto v = numbers(c, j, p, 3);
    return {v[0], v[1], v[2]};
}

std::string string(const Ctx& c, const json& j, const Ptr& p) {
    if (!j.is_string()) c.fail(p, "expected a string, got " + shown(j));
    return j.get<std::string>();
}

// ---- top level ----

ImplicitSolverSettings parseSolver(const Ctx& c, const json& j, const Ptr& p) {
    checkObject(
        c, j, p,
        {"tolerance", "max_iterations", "newton_steps", "newton_tolerance", "line_search", "contact_margin"});
    ImplicitSolverSettings s;
    if (const json* v = find(j, "tolerance")) {
        s.tolerance = positive(c, *v, p / "tolerance");
        if (s.tolerance >= 1.0)
            c.fail(p / "tolerance", "expected a relative residual in (0, 1), got " + shown(*v));
    }
    if (const json* v = find(j, "max_iterations"))
        s.maxIterations = integer(c, *v, p / "max_iterations", 1, 1024);
    if (const json* v = find(j, "newton_steps")) s.newtonSteps = integer(c, *v, p / "newton_steps", 1, 4);
    if (const json* v = find(j, "newton_tolerance")) {
        s.newtonTolerance = number(c, *v, p / "newton_tolerance");
        if (!(s.newtonTolerance >= 0.0 && s.newtonTolerance <= 1.0))
            c.fail(p / "newton_tolerance",
                   "expected a fraction of the thickness in [0, 1], got " + shown(*v));
    }
    if (const json* v = find(j, "contact_margin")) {
        s.contactMargin = number(c, *v, p / "contact_margin");
        if (!(s.contactMargin >= 0.0 && s.contactMargin <= 4.0))
            c.fail(p / "contact_margin", "expected a multiple of the thickness in [0, 4], got " + shown(*v));
    }
    if (const json* v = find(j, "line_search")) {
        if (!v->is_boolean()) c.fail(p / "line_search", "expected true or false, got " + shown(*v));
        s.lineSearch = v->get<bool>();
    }
    return s;
}

TimeSettings parseTime(const Ctx& c, const json& j, const Ptr& p) {
    checkObject(c, j, p, {"dt", "integrator", "substeps", "solver", "frames"});
    TimeSettings t;
    if (const json* v = find(j, "dt")) t.dt = positive(c, *v, p / "dt");
    if (const json* v = find(j, "integrator")) {
        const std::optional<Integrator> kind = integratorFromName(string(c, *v, p / "integrator"));
        if (!kind)
            c.fail(p / "integrator", "expected \"symplectic_euler\" or \"implicit_euler\", got " + shown(*v));
        t.integrator = *kind;
    }
    if (const json* v = find(j, "solver")) {
        if (t.integrator != Integrator::ImplicitEuler)
            c.fail(p / "solver", "given but /time/integrator is not \"implicit_euler\" (only the implicit "
                                 "integrator solves a linear system)");
        t.solver = parseSolver(c, *v, p / "solver");
    }
    if (const json* v = find(j, "substeps")) {
        if (v->is_string()) {
            if (v->get<std::string>() != "auto")
                c.fail(p / "substeps", "expected \"auto\" or a positive integer, got " + shown(*v));
            t.substeps = 0;
        } else {
            if (!v->is_number_integer() || v->get<long long>() < 1)
                c.fail(p / "substeps", "expected \"auto\" or a positive integer, got " + shown(*v));
            t.substeps = integer(c, *v, p / "substeps", 1, 1000000);
        }
    }
    if (const json* v = find(j, "frames")) t.frames = integer(c, *v, p / "frames", 1, 100000000);
    return t;
}

EffectSet parseEffects(const Ctx& c, const json& j, const Ptr& p) {
    if (!j.is_array()) c.fail(p, "expected an array of effect names, got " + shown(j));
    EffectSet set;
    for (std::size_t i = 0; i < j.size(); ++i) {
        const std::string name = string(c, j[i], p / i);
        const auto e = parseEffect(name);
        if (!e) {
            std::string known;
            for (Effect k : kAllEffects) known += (known.empty() ? "" : ", ") + std::string(effectName(k));
            c.fail(p / i, "unknown effect '" + name + "'; known effects: " + known);
        }
        if (set.has(*e)) c.fail(p / i, "effect '" + name + "' is listed twice");
        set.insert(*e);
    }
    return set;
}

// ---- objects ----

enum class Shape { Cloth, Surface, Volume };

/// Spring parameters as written; which ones are allowed depends on the shape.
struct SpringParams {
    double stiffness = 0.0;
    double damping = 0.0;
    double shear = 0.0;
    double bend = 0.0;
};

SpringParams parseSprings(const Ctx& c, const json& j, const Ptr& p, Shape shape) {
    switch (shape) {
    case Shape::Cloth:
        checkObject(c, j, p, {"stiffness", "damping", "shear_stiffness", "bend_stiffness"});
        break;
    case Shape::Surface:
        checkObject(c, j, p, {"stiffness", "damping", "bend_stiffness"});
        break;
    case Shape::Volume:
        checkObject(c, j, p, {"stiffness", "damping"});
        break;
    }
    SpringParams s;
    s.stiffness = positive(c, require(c, j, p, "stiffness"), p / "stiffness");
    if (const json* v = find(j, "damping")) s.damping = nonNegative(c, *v, p / "damping");
    // Cloth defaults follow the usual stiffness ordering: shear as stiff as structural, bending
    // an order of magnitude softer. Meshes get bending only when asked for.
    s.shear = s.stiffness;
    s.bend = shape == Shape::Cloth ? s.stiffness / 10.0 : 0.0;
    if (const json* v = find(j, "shear_stiffness")) s.shear = nonNegative(c, *v, p / "shear_stiffness");
    if (const json* v = find(j, "bend_stiffness")) s.bend = nonNegative(c, *v, p / "bend_stiffness");
    return s;
}

std::string lowerExtension(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
    return ext;
}

Shape meshShape(const Ctx& c, const std::string& file, const Ptr& p) {
    const std::string ext = lowerExtension(file);
    if (ext == ".obj" || ext == ".ply" || ext == ".gltf" || ext == ".glb") return Shape::Surface;
    if (ext == ".msh" || ext == ".node") return Shape::Volume;
    c.fail(p, "unsupported mesh file '" + file +
                  "'; supported: .obj .ply .gltf .glb (surface), .msh (Gmsh tets), .node (TetGen tets, .ele "
                  "beside it)");
}

Shape generatorShape(const Ctx& c, const json& g, const Ptr& p) {
    if (!g.is_object()) c.fail(p, "expected an object, got " + shown(g));
    const std::string type = string(c, require(c, g, p, "type"), p / "type");
    if (type == "cloth") return Shape::Cloth;
    if (type == "tube") return Shape::Surface;
    if (type == "tet_box" || type == "sphere") return Shape::Volume;
    c.fail(p / "type", "unknown generator '" + type + "'; known generators: cloth, tube, tet_box, sphere");
}

Body generate(const Ctx& c, const json& g, const Ptr& p, const SpringParams& springs) {
    const std::string type = g["type"].get<std::string>();
    if (type == "cloth") {
        checkObject(c, g, p, {"type", "size", "resolution"});
        const Ptr ps = p / "size", pr = p / "resolution";
        const json& size = require(c, g, p, "size");
        const json& res = require(c, g, p, "resolution");
        if (!size.is_array() || size.size() != 2)
            c.fail(ps, "expected [width, height] in m, got " + shown(size));
        if (!res.is_array() || res.size() != 2)
            c.fail(pr, "expected [nx, ny] node counts, got " + shown(res));
        const double w = positive(c, size[0], ps / 0), h = positive(c, size[1], ps / 1);
        const int nx = integer(c, res[0], pr / 0, 2, 4096), ny = integer(c, res[1], pr / 1, 2, 4096);
        return detail::generateCloth(w, h, nx, ny, springs.shear > 0.0, springs.bend > 0.0);
    }
    if (type == "tube") {
        checkObject(c, g, p, {"type", "radius", "length", "resolution", "bend_deg"});
        const Ptr pr = p / "resolution";
        const double radius = positive(c, require(c, g, p, "radius"), p / "radius");
        const double length = positive(c, require(c, g, p, "length"), p / "length");
        const json& res = require(c, g, p, "resolution");
        if (!res.is_array() || res.size() != 2)
            c.fail(pr, "expected [around, along] node counts (per ring, rings), got " + shown(res));
        const int around = integer(c, res[0], pr / 0, 3, 4096), along = integer(c, res[1], pr / 1, 2, 4096);
        double bend = 0.0;
        if (const json* v = find(g, "bend_deg")) {
            bend = number(c, *v, p / "bend_deg");
            if (!(bend >= 0.0 && bend < 180.0))
                c.fail(p / "bend_deg", "expected an angle in degrees in [0, 180), got " + shown(*v));
            // The arc's radius is the bent third's length over its angle; a tube as wide folds its
            // inner side onto itself.
            const double arcRadius = length / 3.0 / (bend * std::numbers::pi / 180.0);
            if (bend > 0.0 && !(radius < arcRadius))
                c.fail(p / "bend_deg",
                       "the bend's arc radius (" + std::to_string(arcRadius) +
                           " m: a third of the length over the angle) must exceed the radius " +
                           std::to_string(radius) + " m, or the rings cross inside the bend");
        }
        return detail::generateTube(radius, length, around, along, bend);
    }
    if (type == "tet_box") {
        checkObject(c, g, p, {"type", "size", "resolution"});
        const Ptr ps = p / "size", pr = p / "resolution";
        const json& size = require(c, g, p, "size");
        const json& res = require(c, g, p, "resolution");
        if (!size.is_array() || size.size() != 3) c.fail(ps, "expected [x, y, z] in m, got " + shown(size));
        if (!res.is_array() || res.size() != 3)
            c.fail(pr, "expected [cx, cy, cz] cell counts, got " + shown(res));
        glm::dvec3 s;
        std::array<int, 3> cells{};
        for (std::size_t i = 0; i < 3; ++i) {
            s[static_cast<glm::length_t>(i)] = positive(c, size[i], ps / i);
            cells[i] = integer(c, res[i], pr / i, 1, 512);
        }
        return detail::generateTetBox(s, cells);
    }
    checkObject(c, g, p, {"type", "radius", "subdivisions"});
    const double radius = positive(c, require(c, g, p, "radius"), p / "radius");
    int subdivisions = 2;
    // 7 subdivisions is already 164k faces; beyond that the node count explodes (×4 per level).
    if (const json* v = find(g, "subdivisions")) subdivisions = integer(c, *v, p / "subdivisions", 0, 7);
    return detail::generateSphere(radius, subdivisions);
}

Body loadMesh(const Ctx& c, const std::string& file, const Ptr& p, Shape shape) {
    std::filesystem::path path(file);
    if (path.is_relative()) path = c.baseDir / path;
    Body body;
    try {
        if (shape == Shape::Surface) {
            detail::SurfaceMesh m = detail::importSurfaceMesh(path);
            body.positions = std::move(m.positions);
            body.faces = std::move(m.faces);
        } else {
            detail::TetMesh m =
                lowerExtension(path) == ".msh" ? detail::readGmsh(path) : detail::readTetGen(path);
            body.positions = std::move(m.positions);
            body.tets = std::move(m.tets);
            body.faces = detail::boundaryFaces(body.tets, path.string());
            body.springs = detail::tetEdgeSprings(body.tets);
        }
    } catch (const Error& e) {
        c.fail(p, e.what());
    }
    return body;
}

glm::dvec3 rotateAxis(const glm::dvec3& v, int axis, double radians) {
    const double cs = std::cos(radians), sn = std::sin(radians);
    switch (axis) {
    case 0:
        return {v.x, cs * v.y - sn * v.z, sn * v.y + cs * v.z};
    case 1:
        return {cs * v.x + sn * v.z, v.y, -sn * v.x + cs * v.z};
    default:
        return {cs * v.x - sn * v.y, sn * v.x + cs * v.y, v.z};
    }
}

void applyTransform(const Ctx& c, const json& j, const Ptr& p, Body& body) {
    checkObject(c, j, p, {"translate", "rotate_deg", "scale"});
    glm::dvec3 translate(0.0), rotate(0.0), scale(1.0);
    if (const json* v = find(j, "translate")) translate = vec3(c, *v, p / "translate");
    if (const json* v = find(j, "rotate_deg")) rotate = vec3(c, *v, p / "rotate_deg");
    if (const json* v = find(j, "scale")) {
        // Positive scales only: a mirror would turn every face and tet inside out.
        if (v->is_array()) {
            for (std::size_t i = 0; i < v->size() && i < 3; ++i) positive(c, (*v)[i], p / "scale" / i);
            scale = vec3(c, *v, p / "scale");
        } else {
            scale = glm::dvec3(positive(c, *v, p / "scale"));
        }
    }
    const double toRad = std::numbers::pi / 180.0;
    const auto transform = [&](glm::dvec3& x) {
        glm::dvec3 y = x * scale;
        for (int axis = 0; axis < 3; ++axis) y = rotateAxis(y, axis, rotate[axis] * toRad);
        x = y + translate;
    };
    for (glm::dvec3& x : body.positions) transform(x);
    if (body.observer) transform(*body.observer);
    if (body.observerEnd) transform(*body.observerEnd);
    for (std::array<glm::dvec3, 2>& bone : body.skeleton) {
        transform(bone[0]);
        transform(bone[1]);
    }
}

/// "observer": a point [x, y, z], or a segment [[x, y, z], [x, y, z]] with two different ends.
void parseObserver(const Ctx& c, const json& j, const Ptr& p, Body& body) {
    if (!(j.is_array() && j.size() == 2 && j[0].is_array())) {
        body.observer = vec3(c, j, p);
        return;
    }
    body.observer = vec3(c, j[0], p / 0);
    body.observerEnd = vec3(c, j[1], p / 1);
    if (*body.observer == *body.observerEnd)
        c.fail(p, "a segment observer's two ends must differ (a point observer is [x, y, z])");
}

/// "skeleton": [[[x, y, z], [x, y, z]], ...], one or more bones, each two different ends.
void parseSkeleton(const Ctx& c, const json& j, const Ptr& p, Body& body) {
    if (!j.is_array() || j.empty())
        c.fail(p, "expected an array of bones [[x, y, z], [x, y, z]], got " + shown(j));
    for (std::size_t b = 0; b < j.size(); ++b) {
        const json& bone = j[b];
        if (!bone.is_array() || bone.size() != 2)
            c.fail(p / b, "expected a bone [[x, y, z], [x, y, z]] (its two ends), got " + shown(bone));
        const glm::dvec3 a = vec3(c, bone[0], p / b / 0), e = vec3(c, bone[1], p / b / 1);
        if (a == e) c.fail(p / b, "a bone's two ends must differ");
        body.skeleton.push_back({a, e});
    }
}

void applyPinned(const Ctx& c, const json& j, const Ptr& p, Body& body) {
    const std::size_t n = body.positions.size();
    if (j.is_array()) {
        for (std::size_t i = 0; i < j.size(); ++i)
            body.pinned[static_cast<std::size_t>(integer(c, j[i], p / i, 0, static_cast<long long>(n) - 1))] =
                1;
        return;
    }
    if (!j.is_object())
        c.fail(p, "expected an array of node indices or {\"inside\": {...}}, got " + shown(j));
    checkObject(c, j, p, {"inside"});
    const Ptr pi = p / "inside";
    const json& box = require(c, j, p, "inside");
    checkObject(c, box, pi, {"min", "max"});
    const glm::dvec3 lo = vec3(c, require(c, box, pi, "min"), pi / "min");
    const glm::dvec3 hi = vec3(c, require(c, box, pi, "max"), pi / "max");
    if (lo.x > hi.x || lo.y > hi.y || lo.z > hi.z) c.fail(pi, "min must not exceed max on any axis");
    std::size_t count = 0;
    for (std::size_t v = 0; v < n; ++v) {
        const glm::dvec3& x = body.positions[v];
        if (x.x >= lo.x && x.x <= hi.x && x.y >= lo.y && x.y <= hi.y && x.z >= lo.z && x.z <= hi.z) {
            body.pinned[v] = 1;
            ++count;
        }
    }
    // An empty box is almost always a box written for the untransformed mesh.
    if (count == 0) c.fail(pi, "the box contains no node (it is in world space, after the transform)");
}

Body parseObject(const Ctx& c, const json& j, const Ptr& p, const EffectSet& effects, std::size_t index) {
    checkObject(c, j, p,
                {"name", "mesh", "generator", "transform", "velocity", "angular_velocity", "mass", "density",
                 "springs", "pinned", "observer", "skeleton"});
    const json* mesh = find(j, "mesh");
    const json* gen = find(j, "generator");
    if ((mesh == nullptr) == (gen == nullptr)) c.fail(p, "give exactly one of 'mesh' and 'generator'");

    const Shape shape = mesh != nullptr ? meshShape(c, string(c, *mesh, p / "mesh"), p / "mesh")
                                        : generatorShape(c, *gen, p / "generator");
    SpringParams sp;
    const json* springs = find(j, "springs");
    if (effects.has(Effect::Springs)) {
        if (springs == nullptr) c.fail(p / "springs", "required because 'springs' is in /effects");
        sp = parseSprings(c, *springs, p / "springs", shape);
    } else if (springs != nullptr) {
        c.fail(p / "springs", "given but 'springs' is not in /effects (remove it or add the effect)");
    }

    Body body = mesh != nullptr ? loadMesh(c, mesh->get<std::string>(), p / "mesh", shape)
                                : generate(c, *gen, p / "generator", sp);
    body.name = "object " + std::to_string(index);
    if (const json* v = find(j, "name")) body.name = string(c, *v, p / "name");
    if (const json* v = find(j, "observer")) parseObserver(c, *v, p / "observer", body);
    if (const json* v = find(j, "skeleton")) {
        if (body.observer) c.fail(p / "skeleton", "give 'observer' or 'skeleton', not both");
        parseSkeleton(c, *v, p / "skeleton", body);
    }
    if (const json* v = find(j, "transform")) applyTransform(c, *v, p / "transform", body);

    if (!effects.has(Effect::Springs)) {
        body.springs.clear();
    } else {
        if (shape == Shape::Surface) {
            body.springs = detail::surfaceEdgeSprings(body.faces, SpringKind::Edge);
            if (sp.bend > 0.0) {
                auto bend = detail::surfaceBendSprings(body.faces);
                body.springs.insert(body.springs.end(), bend.begin(), bend.end());
            }
        }
        for (Spring& s : body.springs) {
            s.stiffness = s.kind == SpringKind::Shear  ? sp.shear
                          : s.kind == SpringKind::Bend ? sp.bend
                                                       : sp.stiffness;
            s.damping = sp.damping;
        }
        detail::setRestLengths(body);
        for (std::size_t s = 0; s < body.springs.size(); ++s)
            if (!(body.springs[s].restLength > 0.0))
                c.fail(p, "spring " + std::to_string(s) + " joins nodes " +
                              std::to_string(body.springs[s].a) + " and " +
                              std::to_string(body.springs[s].b) +
                              ", which are at the same position (zero rest length)");
    }

    // Mass: lumped area (surfaces) or volume (tets), scaled to the total or by the density.
    const json* mass = find(j, "mass");
    const json* density = find(j, "density");
    if ((mass == nullptr) == (density == nullptr))
        c.fail(
            p,
            "give exactly one of 'mass' (total kg) and 'density' (kg/m^3 for volumes, kg/m^2 for surfaces)");
    std::vector<double> lump;
    try {
        const std::string what = mesh != nullptr ? mesh->get<std::string>()
                                                 : "generator '" + (*gen)["type"].get<std::string>() + "'";
        lump = detail::lumpedMeasure(body.positions, body.faces, body.tets, what);
    } catch (const Error& e) {
        c.fail(mesh != nullptr ? p / "mesh" : p / "generator", e.what());
    }
    double factor = 0.0;
    if (mass != nullptr) {
        const double total = positive(c, *mass, p / "mass");
        double measure = 0.0;
        for (double l : lump) measure += l;
        factor = total / measure;
    } else {
        factor = positive(c, *density, p / "density");
    }
    body.masses.resize(lump.size());
    for (std::size_t v = 0; v < lump.size(); ++v) body.masses[v] = lump[v] * factor;

    body.velocities.assign(body.positions.size(), glm::dvec3(0.0));
    body.pinned.assign(body.positions.size(), 0);
    glm::dvec3 velocity(0.0), omega(0.0);
    if (const json* v = find(j, "velocity")) velocity = vec3(c, *v, p / "velocity");
    if (const json* v = find(j, "angular_velocity")) omega = vec3(c, *v, p / "angular_velocity");
    glm::dvec3 centre(0.0);
    double total = 0.0;
    for (std::size_t v = 0; v < body.positions.size(); ++v) {
        centre += body.masses[v] * body.positions[v];
        total += body.masses[v];
    }
    centre /= total;
    for (std::size_t v = 0; v < body.positions.size(); ++v)
        body.velocities[v] = velocity + glm::cross(omega, body.positions[v] - centre);
    if (const json* v = find(j, "pinned")) applyPinned(c, *v, p / "pinned", body);
    return body;
}

constexpr const char* kBroadPhaseNames = "\"octree\", \"masked\", \"all_pairs\" or \"bvh\"";
constexpr const char* kResponseNames = "\"penalty\", \"bridson\" or \"intersection_free\"";

BvhSettings parseBvh(const Ctx& c, const json& j, const Ptr& p) {
    checkObject(c, j, p, {"rebuild", "visits_per_round"});
    BvhSettings s;
    if (const json* v = find(j, "rebuild")) {
        if (v->is_number_integer() && v->get<long long>() >= 1 && v->get<long long>() <= 1000000) {
            s.rebuild = BvhRebuild::EveryNFrames;
            s.rebuildFrames = static_cast<int>(v->get<long long>());
        } else if (v->is_string() && v->get<std::string>() == "substep") {
            s.rebuild = BvhRebuild::EverySubstep;
        } else if (v->is_string() && v->get<std::string>() == "frame") {
            s.rebuild = BvhRebuild::EveryFrame;
        } else if (v->is_string() && v->get<std::string>() == "never") {
            s.rebuild = BvhRebuild::Never;
        } else {
            c.fail(p / "rebuild", "expected \"substep\", \"frame\", \"never\" or a number of frames "
                                  "1 ... 1000000, got " +
                                      shown(*v));
        }
    }
    if (const json* v = find(j, "visits_per_round")) {
        if (!v->is_number_integer() || v->get<long long>() < 1 || v->get<long long>() > 65534)
            c.fail(p / "visits_per_round", "expected an integer in 1 ... 65534, got " + shown(*v));
        s.visitsPerRound = static_cast<std::uint32_t>(v->get<long long>());
    }
    return s;
}

CcdSettings parseCcd(const Ctx& c, const json& j, const Ptr& p) {
    checkObject(c, j, p, {"budget", "min_separation"});
    CcdSettings s;
    if (const json* v = find(j, "budget")) {
        // llvmpipe ends a shader invocation after 65,535 loop iterations; a box costs three.
        if (!v->is_number_integer() || v->get<long long>() < 1 || v->get<long long>() > 21844)
            c.fail(p / "budget", "expected an integer in 1 ... 21844, got " + shown(*v));
        s.budget = static_cast<std::uint32_t>(v->get<long long>());
    }
    if (const json* v = find(j, "min_separation")) s.minSeparation = nonNegative(c, *v, p / "min_separation");
    return s;
}

/// A setting of radial culling's: refused unless the scene asks for that culling; `why` says what
/// the setting serves.
void requireRadial(const Ctx& c, const CollisionSettings& s, const Ptr& p, const std::string& why) {
    if (s.culling != Culling::Radial) c.fail(p, why + ": add \"culling\": \"radial\"");
}

CollisionSettings parseCollision(const Ctx& c, const json& j, const Ptr& p) {
    checkObject(c, j, p,
                {"broad_phase",
                 "octree_depth",
                 "precision",
                 "response",
                 "thickness",
                 "stiffness",
                 "damping",
                 "friction",
                 "restitution",
                 "restitution_iterations",
                 "relaxation_time",
                 "initial_capacity",
                 "bvh",
                 "detection",
                 "ccd",
                 "energy_guard",
                 "response_iterations",
                 "culling",
                 "ghost_max_perimeter",
                 "observers",
                 "cluster_max_angle",
                 "cluster_max_faces"});
    CollisionSettings s;
    if (const json* v = find(j, "broad_phase")) {
        const std::optional<BroadPhase> kind = broadPhaseFromName(string(c, *v, p / "broad_phase"));
        if (!kind)
            c.fail(p / "broad_phase", "unknown broad phase " + shown(*v) + "; expected " + kBroadPhaseNames);
        s.broadPhase = *kind;
    }
    if (const json* v = find(j, "bvh")) s.bvh = parseBvh(c, *v, p / "bvh");
    if (const json* v = find(j, "detection")) {
        const std::string name = string(c, *v, p / "detection");
        if (name == "discrete")
            s.detection = Detection::Discrete;
        else if (name == "continuous")
            s.detection = Detection::Continuous;
        else
            c.fail(p / "detection",
                   "unknown detection " + shown(*v) + "; expected \"discrete\" or \"continuous\"");
    }
    if (const json* v = find(j, "ccd")) s.ccd = parseCcd(c, *v, p / "ccd");
    if (const json* v = find(j, "octree_depth")) {
        if (!v->is_number_integer() || v->get<long long>() < 1 || v->get<long long>() > 3)
            c.fail(p / "octree_depth",
                   "expected an integer 1, 2 or 3 (8, 64 or 512 boxes per object), got " + shown(*v));
        s.octreeDepth = static_cast<int>(v->get<long long>());
    }
    if (const json* v = find(j, "precision")) {
        const std::string name = string(c, *v, p / "precision");
        if (name == "fast")
            s.precision = TriTriPrecision::Fast;
        else if (name == "robust")
            s.precision = TriTriPrecision::Robust;
        else
            c.fail(p / "precision", "unknown precision " + shown(*v) + "; expected \"fast\" or \"robust\"");
    }
    // The default response is intersection_free (decision 0024, "The default"). Each response
    // brings its detection (detectionOf) unless the scene names one.
    const json* response = find(j, "response");
    if (response) {
        const std::optional<ContactResponse> kind = responseFromName(string(c, *response, p / "response"));
        if (!kind)
            c.fail(p / "response", "unknown response " + shown(*response) + "; expected " + kResponseNames);
        s.response = *kind;
    }
    const bool detectionGiven = find(j, "detection") != nullptr;
    if (s.response == ContactResponse::IntersectionFree) {
        if (detectionGiven && s.detection != Detection::Continuous)
            c.fail(p / "detection",
                   response ? "the intersection_free response needs \"detection\": \"continuous\""
                            : "the default response, intersection_free, needs \"detection\": \"continuous\"; "
                              "name \"response\": \"penalty\" or \"bridson\" to detect discretely");
    } else if (!detectionGiven) {
        s.detection = detectionOf(s.response);
    }
    if (const json* v = find(j, "culling")) {
        const std::string name = string(c, *v, p / "culling");
        if (name == "none")
            s.culling = Culling::None;
        else if (name == "radial")
            s.culling = Culling::Radial;
        else
            c.fail(p / "culling", "unknown culling " + shown(*v) + "; expected \"none\" or \"radial\"");
        if (s.culling == Culling::Radial && s.response != ContactResponse::IntersectionFree)
            c.fail(p / "culling",
                   "radial culling needs \"response\": \"intersection_free\" (its premise is a "
                   "substep that starts intersection-free, which only that response keeps; decision 0025)");
    }
    if (const json* v = find(j, "ghost_max_perimeter")) {
        requireRadial(c, s, p / "ghost_max_perimeter", "ghost triangles close holes for radial culling only");
        s.ghostMaxPerimeter = nonNegative(c, *v, p / "ghost_max_perimeter");
    }
    if (const json* v = find(j, "observers")) {
        requireRadial(c, s, p / "observers", "observers serve radial culling only");
        const std::string name = string(c, *v, p / "observers");
        if (name == "auto")
            s.observers = RadialObservers::Auto;
        else if (name == "objects")
            s.observers = RadialObservers::Objects;
        else if (name == "clusters")
            s.observers = RadialObservers::Clusters;
        else
            c.fail(p / "observers",
                   "unknown observers " + shown(*v) + "; expected \"auto\", \"objects\" or \"clusters\"");
    }
    if (const json* v = find(j, "cluster_max_angle")) {
        requireRadial(c, s, p / "cluster_max_angle", "clusters serve radial culling only");
        const double degrees =
            number(c, *v, p / "cluster_max_angle", "an angle in degrees, above 0 and below 90");
        if (!(degrees > 0.0 && degrees < 90.0))
            c.fail(p / "cluster_max_angle",
                   "expected an angle in degrees, above 0 and below 90, got " + shown(*v));
        s.clusterMaxAngle = degrees * std::numbers::pi / 180.0;
    }
    if (const json* v = find(j, "cluster_max_faces")) {
        requireRadial(c, s, p / "cluster_max_faces", "clusters serve radial culling only");
        if (!v->is_number_integer() || v->get<long long>() < 0 || v->get<long long>() > 0xffffffffLL)
            c.fail(p / "cluster_max_faces",
                   "expected a whole number of faces >= 0 (0: no limit), got " + shown(*v));
        s.clusterMaxFaces = static_cast<std::uint32_t>(v->get<long long>());
    }
    if (const json* v = find(j, "energy_guard")) {
        if (!v->is_boolean()) c.fail(p / "energy_guard", "expected true or false, got " + shown(*v));
        if (s.response != ContactResponse::IntersectionFree)
            c.fail(p / "energy_guard", "only the \"intersection_free\" response has an energy guard");
        s.energyGuard = v->get<bool>();
    }
    if (const json* v = find(j, "response_iterations")) {
        if (s.response != ContactResponse::IntersectionFree)
            c.fail(p / "response_iterations",
                   "only the \"intersection_free\" response iterates its velocity response");
        s.responseIterations = integer(c, *v, p / "response_iterations", 1, 64);
    }
    if (const json* v = find(j, "thickness")) {
        s.thickness = number(c, *v, p / "thickness", "a positive number of metres");
        if (!(s.thickness > 0.0))
            c.fail(p / "thickness", "expected a positive number of metres, got " + shown(*v));
    }
    if (const json* v = find(j, "stiffness")) {
        s.stiffness = number(c, *v, p / "stiffness", "a positive number of N/m");
        if (!(s.stiffness > 0.0))
            c.fail(p / "stiffness", "expected a positive number of N/m, got " + shown(*v));
    }
    if (const json* v = find(j, "damping")) s.damping = nonNegative(c, *v, p / "damping");
    if (const json* v = find(j, "friction")) s.friction = nonNegative(c, *v, p / "friction");
    if (const json* v = find(j, "restitution")) {
        if (s.response != ContactResponse::IntersectionFree)
            c.fail(p / "restitution",
                   "only the \"intersection_free\" response has a restitution between bodies");
        s.restitution = number(c, *v, p / "restitution", "a number in [0, 1]");
        if (!(s.restitution >= 0.0 && s.restitution <= 1.0))
            c.fail(p / "restitution", "expected a number in [0, 1], got " + shown(*v));
    }
    if (const json* v = find(j, "restitution_iterations")) {
        if (!(s.restitution > 0.0))
            c.fail(p / "restitution_iterations", "only a restitution above 0 has iterations");
        s.restitutionIterations = integer(c, *v, p / "restitution_iterations", 1, 64);
    }
    if (const json* v = find(j, "relaxation_time")) {
        if (s.response == ContactResponse::Penalty)
            c.fail(
                p / "relaxation_time",
                "the penalty response does not relax: only \"bridson\" and \"intersection_free\" have one");
        s.relaxationTime = number(c, *v, p / "relaxation_time", "a positive number of seconds");
        if (!(s.relaxationTime > 0.0))
            c.fail(p / "relaxation_time", "expected a positive number of seconds, got " + shown(*v));
    }
    if (const json* v = find(j, "initial_capacity")) {
        if (!v->is_number_integer() || v->get<long long>() < 1 || v->get<long long>() > (1LL << 30))
            c.fail(p / "initial_capacity", "expected an integer in 1 ... 2^30, got " + shown(*v));
        s.initialCapacity = static_cast<std::uint32_t>(v->get<long long>());
    }
    return s;
}

CameraSettings parseCamera(const Ctx& c, const json& j, const Ptr& p) {
    checkObject(c, j, p, {"eye", "target", "up", "fov_deg"});
    CameraSettings cam;
    cam.eye = vec3(c, require(c, j, p, "eye"), p / "eye");
    cam.target = vec3(c, require(c, j, p, "target"), p / "target");
    if (const json* v = find(j, "up")) cam.up = vec3(c, *v, p / "up");
    if (const json* v = find(j, "fov_deg")) {
        cam.fovDeg = number(c, *v, p / "fov_deg", "a number of degrees in (0, 180)");
        if (!(cam.fovDeg > 0.0 && cam.fovDeg < 180.0))
            c.fail(p / "fov_deg", "expected a number of degrees in (0, 180), got " + shown(*v));
    }
    const glm::dvec3 forward = cam.target - cam.eye;
    if (!(glm::length(forward) > 0.0))
        c.fail(p / "target", "must differ from eye (the camera looks from eye to target)");
    if (!(glm::length(cam.up) > 0.0))
        c.fail(p / "up", "expected a non-zero vector, got " + shown(*find(j, "up")));
    if (glm::length(glm::cross(glm::normalize(forward), glm::normalize(cam.up))) < 1e-6)
        c.fail(p / "up", "must not be parallel to the view direction (target - eye)");
    return cam;
}

Scene parseRoot(const Ctx& c, const json& root) {
    const Ptr p;
    checkObject(c, root, p,
                {"format_version", "name", "effects", "time", "gravity", "damping", "wind", "ground",
                 "collision", "camera", "objects"});
    const json& version = require(c, root, p, "format_version");
    if (!version.is_number_integer() || version.get<long long>() != Scene::kFormatVersion)
        c.fail(p / "format_version", "unsupported format version " + shown(version) +
                                         "; supported versions: " + std::to_string(Scene::kFormatVersion));
    Scene scene;
    scene.effects = parseEffects(c, require(c, root, p, "effects"), p / "effects");
    if (const json* v = find(root, "name")) scene.name = string(c, *v, p / "name");
    if (const json* v = find(root, "time")) scene.time = parseTime(c, *v, p / "time");

    // A setting whose effect is off would silently do nothing: refuse it.
    const auto gated = [&](const char* key, Effect e) -> const json* {
        const json* v = find(root, key);
        if (v != nullptr && !scene.effects.has(e))
            c.fail(p / key, std::string("given but '") + std::string(effectName(e)) +
                                "' is not in /effects (remove it or add the effect)");
        return v;
    };
    if (const json* v = gated("gravity", Effect::Gravity)) scene.gravity = vec3(c, *v, p / "gravity");
    if (const json* v = gated("damping", Effect::Damping)) scene.damping = nonNegative(c, *v, p / "damping");
    if (const json* v = gated("wind", Effect::Wind)) {
        const Ptr pw = p / "wind";
        checkObject(c, *v, pw, {"velocity", "drag"});
        if (const json* w = find(*v, "velocity")) scene.wind.velocity = vec3(c, *w, pw / "velocity");
        if (const json* w = find(*v, "drag")) scene.wind.drag = nonNegative(c, *w, pw / "drag");
    }
    if (const json* v = gated("ground", Effect::Ground)) {
        const Ptr pg = p / "ground";
        checkObject(c, *v, pg, {"height", "restitution", "friction"});
        if (const json* w = find(*v, "height")) scene.ground.height = number(c, *w, pg / "height");
        if (const json* w = find(*v, "restitution")) {
            scene.ground.restitution = number(c, *w, pg / "restitution", "a number in [0, 1]");
            if (scene.ground.restitution < 0.0 || scene.ground.restitution > 1.0)
                c.fail(pg / "restitution", "expected a number in [0, 1], got " + shown(*w));
        }
        if (const json* w = find(*v, "friction")) scene.ground.friction = nonNegative(c, *w, pg / "friction");
    }
    if (const json* v = find(root, "collision")) {
        if (!scene.effects.has(Effect::Collisions) && !scene.effects.has(Effect::SelfCollisions))
            c.fail(p / "collision", "given but neither 'collisions' nor 'self_collisions' is in /effects "
                                    "(remove it or add an effect)");
        scene.collision = parseCollision(c, *v, p / "collision");
        const CollisionSettings& col = scene.collision;
        // Only a guard the scene asks for is refused: by default the engine leaves it out where
        // the wind blows (PipelinePlan's energyGuard).
        const json* guard = find(*v, "energy_guard");
        if (guard && col.energyGuard && scene.effects.has(Effect::Wind))
            c.fail(p / "collision" / "energy_guard",
                   "the energy guard needs a closed scene and the wind does work on it: set "
                   "\"energy_guard\": false (decision 0024)");
        if (col.culling == Culling::Radial && !scene.effects.has(Effect::SelfCollisions))
            c.fail(p / "collision" / "culling",
                   "radial culling leaves out self-collision pairs: add \"self_collisions\" to /effects");
    }

    const bool collides = scene.effects.has(Effect::Collisions) || scene.effects.has(Effect::SelfCollisions);
    if (scene.time.solver.newtonSteps > 1 &&
        (!collides || scene.collision.response != ContactResponse::IntersectionFree))
        c.fail(p / "time" / "solver" / "newton_steps",
               "more than 1 Newton step needs the contacts in the solve: \"collision\": {\"response\": "
               "\"intersection_free\"} with a collision effect");
    if (const json* v = find(root, "camera")) scene.camera = parseCamera(c, *v, p / "camera");

    const json& objects = require(c, root, p, "objects");
    if (!objects.is_array() || objects.empty())
        c.fail(p / "objects", "expected a non-empty array of objects");
    for (std::size_t i = 0; i < objects.size(); ++i) {
        scene.bodies.push_back(parseObject(c, objects[i], p / "objects" / i, scene.effects, i));
        const bool radial = collides && scene.collision.culling == Culling::Radial;
        if (scene.bodies.back().observer && !radial)
            c.fail(p / "objects" / i / "observer",
                   "an observer serves radial culling only: add \"collision\": {\"culling\": \"radial\"}");
        if (!scene.bodies.back().skeleton.empty() && !radial)
            c.fail(p / "objects" / i / "skeleton",
                   "a skeleton serves radial culling only: add \"collision\": {\"culling\": \"radial\"}");
    }
    return scene;
}

// Kept identical to scenes/hanging_cloth.json (a unit test compares them).
constexpr const char* kDefaultScene = R"json({
  // The scene `glcollide run` simulates when given none (see defaultScene()): a horizontal
  // cloth pinned at two corners swings down under gravity.
  "format_version": 1,
  "name": "hanging cloth",
  "effects": ["gravity", "springs", "damping"],
  "time": {"dt": 0.016666666666666666, "substeps": "auto", "frames": 240},
  "gravity": [0, -9.81, 0],
  "damping": 0.1,
  "objects": [
    {
      "name": "cloth",
      "generator": {"type": "cloth", "size": [1, 1], "resolution": [32, 32]},
      "transform": {"translate": [0, 1.5, 0], "rotate_deg": [90, 0, 0]},
      "mass": 0.3,
      "springs": {"stiffness": 500, "damping": 0.002, "shear_stiffness": 200, "bend_stiffness": 20},
      "pinned": [0, 31]
    }
  ]
}
)json";

} // namespace

Scene parseScene(const std::string& jsonText, const std::filesystem::path& baseDir,
                 const std::string& sourceName) {
    const Ctx c{sourceName, baseDir};
    json root;
    // nlohmann keeps the last of two equal keys without a word; a duplicated key is as likely a
    // mistake as a typo, so it is an error too. The callback tracks where it is (key or index per
    // open object/array) so the error names the JSON pointer of the second key.
    struct Open {
        bool array = false;
        std::size_t index = 0;         // arrays: index of the next element
        std::string key;               // objects: the key being read
        std::vector<std::string> keys; // objects: keys seen so far
    };
    std::vector<Open> open;
    const auto elementDone = [&] {
        if (!open.empty() && open.back().array) ++open.back().index;
    };
    const json::parser_callback_t noDuplicates = [&](int, json::parse_event_t event, json& parsed) {
        switch (event) {
        case json::parse_event_t::object_start:
            open.push_back(Open{});
            break;
        case json::parse_event_t::array_start:
            open.push_back(Open{true, 0, {}, {}});
            break;
        case json::parse_event_t::object_end:
        case json::parse_event_t::array_end:
            if (!open.empty()) open.pop_back();
            elementDone();
            break;
        case json::parse_event_t::value:
            elementDone();
            break;
        case json::parse_event_t::key: {
            if (open.empty()) break;
            const std::string key = parsed.get<std::string>();
            if (std::find(open.back().keys.begin(), open.back().keys.end(), key) != open.back().keys.end()) {
                Ptr where;
                for (std::size_t i = 0; i + 1 < open.size(); ++i)
                    where = open[i].array ? where / open[i].index : where / open[i].key;
                c.fail(where / key, "duplicate key '" + key + "' (a key may appear only once in an object)");
            }
            open.back().keys.push_back(key);
            open.back().key = key;
            break;
        }
        }
        return true;
    };
    try {
        root = json::parse(jsonText, noDuplicates, true, true);
    } catch (const json::exception& e) { // parse errors, and numbers beyond double range (1e999)
        throw Error(detail::invalidJsonMessage(e, jsonText, sourceName));
    }
    Scene scene = parseRoot(c, root);
    if (scene.name.empty()) scene.name = std::filesystem::path(sourceName).stem().string();
    try {
        validateScene(scene);
    } catch (const Error& e) {
        // validateScene names the scene; make sure the file is named even before sourcePath is set.
        throw Error(sourceName + ": " + e.what());
    }
    return scene;
}

Scene loadScene(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path.string() + ": cannot open scene file");
    std::ostringstream text;
    text << in.rdbuf();
    Scene scene = parseScene(text.str(), path.parent_path(), path.string());
    scene.sourcePath = path;
    return scene;
}

Scene defaultScene() {
    return parseScene(kDefaultScene, {}, "default scene");
}

const char* integratorName(Integrator kind) {
    switch (kind) {
    case Integrator::SymplecticEuler:
        return "symplectic_euler";
    case Integrator::ImplicitEuler:
        return "implicit_euler";
    }
    return "?";
}

std::optional<Integrator> integratorFromName(std::string_view name) {
    for (Integrator kind : {Integrator::SymplecticEuler, Integrator::ImplicitEuler})
        if (name == integratorName(kind)) return kind;
    return std::nullopt;
}

const char* broadPhaseName(BroadPhase kind) {
    switch (kind) {
    case BroadPhase::Octree:
        return "octree";
    case BroadPhase::Masked:
        return "masked";
    case BroadPhase::AllPairs:
        return "all_pairs";
    case BroadPhase::Bvh:
        return "bvh";
    }
    return "?";
}

std::optional<ContactResponse> responseFromName(std::string_view name) {
    if (name == "penalty") return ContactResponse::Penalty;
    if (name == "bridson") return ContactResponse::Bridson;
    if (name == "intersection_free") return ContactResponse::IntersectionFree;
    return std::nullopt;
}

Detection detectionOf(ContactResponse response) {
    return response == ContactResponse::IntersectionFree ? Detection::Continuous : Detection::Discrete;
}

std::optional<BroadPhase> broadPhaseFromName(std::string_view name) {
    for (BroadPhase kind : {BroadPhase::Octree, BroadPhase::Masked, BroadPhase::AllPairs, BroadPhase::Bvh})
        if (name == broadPhaseName(kind)) return kind;
    return std::nullopt;
}

void overrideBroadPhase(Scene& scene, std::string_view name) {
    const std::optional<BroadPhase> kind = broadPhaseFromName(name);
    if (!kind)
        throw Error("--broad-phase: unknown broad phase \"" + std::string(name) + "\"; expected " +
                    kBroadPhaseNames);
    if (!scene.effects.has(Effect::Collisions) && !scene.effects.has(Effect::SelfCollisions))
        throw Error("--broad-phase: scene '" + scene.name +
                    "' lists neither 'collisions' nor 'self_collisions'");
    scene.collision.broadPhase = *kind;
}

} // namespace glcollide
