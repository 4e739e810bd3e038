// The one-declaration rule (docs/design/decisions/0001-ssbo-layout-shared-by-glsl-and-cpp.md), checked
// against the driver: every SSBO block of every embedded shader sits at the binding layout.glsl names, and
// the offsets and strides the driver reports for the shared structs equal the C++ offsetof/sizeof of
// src/core/gpu_layout.hpp.

#include <glcollide/error.hpp>

#include "core/gpu_layout.hpp"
#include "gl/program.hpp"
#include "passes/dynamics_passes.hpp"
#include "support/gl_test_environment.hpp"

#include <gtest/gtest.h>

#include <epoxy/gl.h>

#include <fstream>
#include <algorithm>
#include <array>
#include <map>
#include <sstream>

namespace glcollide {
namespace {

const std::map<std::string, GLint> kExpectedBindings = {
    {"NodePositionsBuf", GLC_BIND_NODE_POSITIONS},
    {"NodeVelocitiesBuf", GLC_BIND_NODE_VELOCITIES},
    {"SpringsBuf", GLC_BIND_SPRINGS},
    {"NodeForcesBuf", GLC_BIND_NODE_FORCES},
    {"FacesBuf", GLC_BIND_FACES},
    {"ObjectsBuf", GLC_BIND_OBJECTS},
    {"NodeSpringOffsetsBuf", GLC_BIND_NODE_SPRING_OFFSETS},
    {"NodeSpringListBuf", GLC_BIND_NODE_SPRING_LIST},
    {"NodeFaceOffsetsBuf", GLC_BIND_NODE_FACE_OFFSETS},
    {"NodeFaceListBuf", GLC_BIND_NODE_FACE_LIST},
    // collision detection (src/passes/collision_detection.cpp, src/passes/broad_phase/)
    {"BoxesBuf", GLC_BIND_BOXES},
    {"IntersectionsBuf", GLC_BIND_INTERSECTIONS},
    {"FaceInfoBuf", GLC_BIND_FACE_INFO},
    {"BoxFaceListBuf", GLC_BIND_BOX_FACE_LIST},
    {"FacePairsBuf", GLC_BIND_FACE_PAIRS},
    {"BoxMaskBuf", GLC_BIND_BOX_MASK},
    {"BoxFaceOffsetsBuf", GLC_BIND_BOX_FACE_OFFSETS},
    {"BoxPairsBuf", GLC_BIND_BOX_PAIRS},
    {"CollisionCountersBuf", GLC_BIND_COLLISION_COUNTERS},
    {"DispatchArgsBuf", GLC_BIND_DISPATCH_ARGS},
    {"UndecidedBuf", GLC_BIND_UNDECIDED},
    // Representative-Triangle feature pairs (src/passes/collision/feature_pairs.cpp)
    {"VertexFacePairsBuf", GLC_BIND_VERTEX_FACE_PAIRS},
    {"FeatureOrphansBuf", GLC_BIND_FEATURE_ORPHANS},
    {"EdgeEdgePairsBuf", GLC_BIND_EDGE_EDGE_PAIRS},
    // tri-tri queries (src/passes/tri_tri_query_pass.cpp)
    {"QueryTrianglesBuf", GLC_BIND_QUERY_TRIANGLES},
    {"QueryResultsBuf", GLC_BIND_QUERY_RESULTS},
    {"QueryStatsBuf", GLC_BIND_QUERY_STATS},
    // CCD queries (src/passes/ccd_query_pass.cpp)
    {"CcdQueriesBuf", GLC_BIND_CCD_QUERIES},
    {"CcdResultsBuf", GLC_BIND_CCD_RESULTS},
    // non-finite check of NodeUpdate (EngineOptions::checkFinite)
    {"ContactForcesBuf", GLC_BIND_CONTACT_FORCES},
    {"HealthBuf", GLC_BIND_HEALTH},
    {"BvhBoxesBuf", GLC_BIND_BVH_BOXES},
    {"BvhLinksBuf", GLC_BIND_BVH_LINKS},
    {"BvhVisitsBuf", GLC_BIND_BVH_VISITS},
    {"BvhResumeBuf", GLC_BIND_BVH_RESUME},
    {"BvhBoundsBuf", GLC_BIND_BVH_BOUNDS},
    {"SortKeysInBuf", GLC_BIND_SORT_KEYS_IN},
    {"SortValuesInBuf", GLC_BIND_SORT_VALUES_IN},
    {"SortKeysOutBuf", GLC_BIND_SORT_KEYS_OUT},
    {"SortValuesOutBuf", GLC_BIND_SORT_VALUES_OUT},
    {"SortBlockCountsBuf", GLC_BIND_SORT_BLOCK_COUNTS},
    // the implicit solver (src/passes/implicit_solver.cpp) and the heavy-row layout of SpringUpdate
    {"ResidualBuf", GLC_BIND_SOLVER_RESIDUAL},
    {"PreconditionedBuf", GLC_BIND_SOLVER_PRECONDITIONED},
    {"DirectionInBuf", GLC_BIND_SOLVER_DIRECTION_IN},
    {"DirectionOutBuf", GLC_BIND_SOLVER_DIRECTION_OUT},
    {"ProductBuf", GLC_BIND_SOLVER_PRODUCT},
    {"BlockInverseBuf", GLC_BIND_SOLVER_BLOCK_INVERSE},
    {"PartialsRBuf", GLC_BIND_SOLVER_PARTIALS_R},
    {"PartialsPqBuf", GLC_BIND_SOLVER_PARTIALS_PQ},
    {"SolverStateBuf", GLC_BIND_SOLVER_STATE},
    {"HeavyNodesBuf", GLC_BIND_HEAVY_NODES},
    {"ImplicitContactsBuf", GLC_BIND_IMPLICIT_CONTACTS},
    {"NodeContactCountsBuf", GLC_BIND_NODE_CONTACT_COUNTS},
    // continuous detection (docs/ccd.md, "In the engine")
    {"PredictedPositionsBuf", GLC_BIND_PREDICTED_POSITIONS},
    {"NodeToiBuf", GLC_BIND_NODE_TOI},
    {"ObjectToiBuf", GLC_BIND_OBJECT_TOI},
    {"TangledBuf", GLC_BIND_TANGLED},
    {"EnergyGuardBuf", GLC_BIND_ENERGY_GUARD},
    // radial view-based culling (src/passes/radial_classify.cpp)
    {"RadialObserversBuf", GLC_BIND_RADIAL_OBSERVERS},
    {"RadialFaceObserverBuf", GLC_BIND_RADIAL_FACE_OBSERVER},
    {"RadialPositiveBuf", GLC_BIND_RADIAL_POSITIVE},
    {"RadialObserverNodesBuf", GLC_BIND_RADIAL_OBSERVER_NODES},
    {"RadialConesBuf", GLC_BIND_RADIAL_CONES},
    {"RadialSegmentsBuf", GLC_BIND_RADIAL_SEGMENTS},
    {"RadialFeetBuf", GLC_BIND_RADIAL_FEET},
    {"RadialNonPositiveBuf", GLC_BIND_RADIAL_NONPOSITIVE},
    {"RadialCellsBuf", GLC_BIND_RADIAL_CELLS},
    {"StartVelocitiesBuf", GLC_BIND_START_VELOCITIES},
    {"ImpactImpulsesBuf", GLC_BIND_IMPACT_IMPULSES},
    {"RadialFreeBuf", GLC_BIND_RADIAL_FREE},
    {"RadialMovedBuf", GLC_BIND_RADIAL_MOVED},
    {"CcdVertexFaceTestsBuf", GLC_BIND_CCD_VERTEX_FACE_TESTS},
    {"CcdEdgeEdgeTestsBuf", GLC_BIND_CCD_EDGE_EDGE_TESTS},
    {"RadialGhostFacesBuf", GLC_BIND_RADIAL_GHOST_FACES},
    {"RadialGhostLoopsBuf", GLC_BIND_RADIAL_GHOST_LOOPS},
    {"RadialGhostPositionsBuf", GLC_BIND_RADIAL_GHOST_POSITIONS},
    {"RadialWindingBuf", GLC_BIND_RADIAL_WINDING},
    {"RadialNodeObserverBuf", GLC_BIND_RADIAL_NODE_OBSERVER},
    {"LineSearchBuf", GLC_BIND_LINE_SEARCH},
    {"LineSearchVelocitiesBuf", GLC_BIND_LINE_SEARCH_VELOCITIES},
    {"UntanglePushBuf", GLC_BIND_UNTANGLE_PUSH},
    {"UntangleCountsBuf", GLC_BIND_UNTANGLE_COUNTS},
};

GLint resourceProperty(GLuint program, GLenum interface, const char* name, GLenum property) {
    const GLuint index = glGetProgramResourceIndex(program, interface, name);
    EXPECT_NE(index, GL_INVALID_INDEX) << name;
    if (index == GL_INVALID_INDEX) return -1;
    GLint value = -1;
    glGetProgramResourceiv(program, interface, index, 1, &property, 1, nullptr, &value);
    return value;
}

// Every embedded shader with all its declared features on, so every block of every shader is seen.
std::vector<gl::ComputeProgram> allPrograms() {
    std::vector<gl::ComputeProgram> p;
    for (const std::string& name : gl::embeddedShaderNames()) p.emplace_back(name, gl::shaderFeatures(name));
    return p;
}

TEST(LayoutGl, EveryBlockOfEveryShaderUsesTheSharedBinding) {
    int blocksSeen = 0, highestBinding = -1;
    for (const gl::ComputeProgram& program : allPrograms()) {
        GLint count = 0;
        glGetProgramInterfaceiv(program.name(), GL_SHADER_STORAGE_BLOCK, GL_ACTIVE_RESOURCES, &count);
        for (GLint i = 0; i < count; ++i) {
            char name[128] = {};
            glGetProgramResourceName(program.name(), GL_SHADER_STORAGE_BLOCK, static_cast<GLuint>(i),
                                     sizeof name, nullptr, name);
            const GLenum property = GL_BUFFER_BINDING;
            GLint binding = -1;
            glGetProgramResourceiv(program.name(), GL_SHADER_STORAGE_BLOCK, static_cast<GLuint>(i), 1,
                                   &property, 1, nullptr, &binding);
            ASSERT_TRUE(kExpectedBindings.count(name)) << program.shaderName() << ": unknown block " << name;
            EXPECT_EQ(binding, kExpectedBindings.at(name)) << program.shaderName() << ": " << name;
            highestBinding = std::max(highestBinding, binding);
            ++blocksSeen;
        }
    }
    EXPECT_GE(blocksSeen, 14); // 6 + 6 + 3 blocks in the three full variants
    // The host-state guard saves and restores bindings 0 .. GLC_BINDING_COUNT-1: exactly the used ones.
    EXPECT_EQ(highestBinding + 1, GLC_BINDING_COUNT);
}

TEST(LayoutGl, NodeArraysHaveVec4StrideForDrawing) {
    for (const gl::ComputeProgram& program : allPrograms()) {
        for (const char* var : {"g_positions[0]", "g_velocities[0]", "g_forces[0]"}) {
            const GLuint index = glGetProgramResourceIndex(program.name(), GL_BUFFER_VARIABLE, var);
            if (index == GL_INVALID_INDEX) continue;             // not every shader declares every array
            const GLenum props[] = {GL_OFFSET, GL_ARRAY_STRIDE}; // an array of vec4, not of structs
            GLint values[2] = {-1, -1};
            glGetProgramResourceiv(program.name(), GL_BUFFER_VARIABLE, index, 2, props, 2, nullptr, values);
            EXPECT_EQ(values[0], 0) << program.shaderName() << " " << var;
            EXPECT_EQ(values[1], static_cast<GLint>(sizeof(gpu::vec4))) << program.shaderName() << " " << var;
        }
    }
}

TEST(LayoutGl, SpringStructMatchesCpp) {
    gl::ComputeProgram program("spring_update");
    const GLuint p = program.name();
    EXPECT_EQ(resourceProperty(p, GL_BUFFER_VARIABLE, "g_springs[0].nodeA", GL_TOP_LEVEL_ARRAY_STRIDE),
              static_cast<GLint>(sizeof(gpu::GpuSpring)));
    const std::pair<const char*, std::size_t> members[] = {
        {"g_springs[0].nodeA", offsetof(gpu::GpuSpring, nodeA)},
        {"g_springs[0].nodeB", offsetof(gpu::GpuSpring, nodeB)},
        {"g_springs[0].restLength", offsetof(gpu::GpuSpring, restLength)},
        {"g_springs[0].stiffness", offsetof(gpu::GpuSpring, stiffness)},
        {"g_springs[0].damping", offsetof(gpu::GpuSpring, damping)},
        {"g_springs[0].object", offsetof(gpu::GpuSpring, object)},
        {"g_springs[0].pad0", offsetof(gpu::GpuSpring, pad0)},
        {"g_springs[0].pad1", offsetof(gpu::GpuSpring, pad1)},
    };
    for (const auto& [name, offset] : members)
        EXPECT_EQ(resourceProperty(p, GL_BUFFER_VARIABLE, name, GL_OFFSET), static_cast<GLint>(offset))
            << name;
}

// GpuObject is not used by a dynamics pass yet; a probe shader built from the same layout.glsl
// text checks it, so the C++ mirror cannot drift before a pass adopts it.
TEST(LayoutGl, ObjectStructMatchesCpp) {
    std::ifstream in(std::string(GLCOLLIDE_SOURCE_DIR) + "/shaders/common/layout.glsl");
    ASSERT_TRUE(in);
    std::stringstream layout;
    layout << in.rdbuf();
    const std::string source =
        "#version 430 core\n" + layout.str() +
        "layout(local_size_x = 1) in;\n"
        "layout(std430, binding = GLC_BIND_OBJECTS) buffer ObjectsBuf { GpuObject g_objects[]; };\n"
        "void main() { GpuObject o = g_objects[0]; g_objects[1] = o; }\n";
    const gl::ComputeProgram probe = gl::ComputeProgram::fromSource("layout_probe", source);
    const GLuint p = probe.name();
    EXPECT_EQ(resourceProperty(p, GL_SHADER_STORAGE_BLOCK, "ObjectsBuf", GL_BUFFER_BINDING),
              GLC_BIND_OBJECTS);
    EXPECT_EQ(resourceProperty(p, GL_BUFFER_VARIABLE, "g_objects[0].firstNode", GL_TOP_LEVEL_ARRAY_STRIDE),
              static_cast<GLint>(sizeof(gpu::GpuObject)));
    const std::pair<const char*, std::size_t> members[] = {
        {"g_objects[0].firstNode", offsetof(gpu::GpuObject, firstNode)},
        {"g_objects[0].nodeCount", offsetof(gpu::GpuObject, nodeCount)},
        {"g_objects[0].firstFace", offsetof(gpu::GpuObject, firstFace)},
        {"g_objects[0].faceCount", offsetof(gpu::GpuObject, faceCount)},
        {"g_objects[0].firstSpring", offsetof(gpu::GpuObject, firstSpring)},
        {"g_objects[0].springCount", offsetof(gpu::GpuObject, springCount)},
    };
    for (const auto& [name, offset] : members)
        EXPECT_EQ(resourceProperty(p, GL_BUFFER_VARIABLE, name, GL_OFFSET), static_cast<GLint>(offset))
            << name;
}

// The collision structs, as the collision shaders see them.
TEST(LayoutGl, CollisionStructsMatchCpp) {
    gl::ComputeProgram update("bb_update"), expand("octree_expand");
    EXPECT_EQ(resourceProperty(update.name(), GL_BUFFER_VARIABLE, "g_boxes[0].lo", GL_TOP_LEVEL_ARRAY_STRIDE),
              static_cast<GLint>(sizeof(gpu::GpuBox)));
    EXPECT_EQ(resourceProperty(update.name(), GL_BUFFER_VARIABLE, "g_boxes[0].lo", GL_OFFSET),
              static_cast<GLint>(offsetof(gpu::GpuBox, lo)));
    EXPECT_EQ(resourceProperty(update.name(), GL_BUFFER_VARIABLE, "g_boxes[0].hi", GL_OFFSET),
              static_cast<GLint>(offsetof(gpu::GpuBox, hi)));
    const GLuint p = expand.name();
    EXPECT_EQ(resourceProperty(p, GL_BUFFER_VARIABLE, "g_faceInfo[0].object", GL_TOP_LEVEL_ARRAY_STRIDE),
              static_cast<GLint>(sizeof(gpu::GpuFaceInfo)));
    const std::pair<const char*, std::size_t> members[] = {
        {"g_faceInfo[0].object", offsetof(gpu::GpuFaceInfo, object)},
        {"g_faceInfo[0].box", offsetof(gpu::GpuFaceInfo, box)},
        {"g_faceInfo[0].owned", offsetof(gpu::GpuFaceInfo, owned)},
        {"g_faceInfo[0].pad0", offsetof(gpu::GpuFaceInfo, pad0)},
        {"g_counters.lists[0].count",
         offsetof(gpu::GpuCollisionCounters, lists) + offsetof(gpu::GpuListCounter, count)},
        {"g_counters.lists[0].capacity",
         offsetof(gpu::GpuCollisionCounters, lists) + offsetof(gpu::GpuListCounter, capacity)},
        {"g_counters.stats[0]", offsetof(gpu::GpuCollisionCounters, stats)},
    };
    for (const auto& [name, offset] : members)
        EXPECT_EQ(resourceProperty(p, GL_BUFFER_VARIABLE, name, GL_OFFSET), static_cast<GLint>(offset))
            << name;
}

// The list array's stride, which the C++ counters index with (GpuListCounter per list).
TEST(LayoutGl, ListCountersHaveTheCppStride) {
    gl::ComputeProgram expand("octree_expand");
    for (std::uint32_t list = 0; list < GLC_LIST_COUNT; ++list) {
        const std::string name = "g_counters.lists[" + std::to_string(list) + "].capacity";
        EXPECT_EQ(resourceProperty(expand.name(), GL_BUFFER_VARIABLE, name.c_str(), GL_OFFSET),
                  static_cast<GLint>(offsetof(gpu::GpuCollisionCounters, lists) +
                                     list * sizeof(gpu::GpuListCounter) +
                                     offsetof(gpu::GpuListCounter, capacity)))
            << name;
    }
}

// The work-group sizes the C++ sizes dispatches with (layout.glsl) are the ones each program
// was compiled with.
TEST(LayoutGl, WorkGroupSizesMatchTheSharedConstants) {
    const std::map<std::string, std::array<GLint, 3>> expected = {
        {"bb_update", {GLC_BB_UPDATE_GROUP, 1, 1}},
        {"octree_box_pairs", {GLC_BOX_PAIR_TILE, GLC_BOX_PAIR_TILE, 1}},
        {"box_mask", {GLC_BOX_PAIR_TILE, GLC_BOX_PAIR_TILE, 1}},
        {"octree_expand", {GLC_EXPAND_GROUP, 1, 1}},
        {"all_face_pairs", {GLC_FACE_PAIR_TILE, GLC_FACE_PAIR_TILE, 1}},
        {"masked_face_pairs", {GLC_FACE_PAIR_TILE, GLC_FACE_PAIR_TILE, 1}},
        {"paper_all_pairs_tri_tri", {GLC_FACE_PAIR_TILE, GLC_FACE_PAIR_TILE, 1}},
        {"paper_masked_tri_tri", {GLC_FACE_PAIR_TILE, GLC_FACE_PAIR_TILE, 1}},
        {"list_dispatch_args", {1, 1, 1}},
        {"radix_count", {GLC_SORT_BLOCK, 1, 1}},
        {"radix_scatter", {GLC_SORT_BLOCK, 1, 1}},
        {"radix_scan", {GLC_SCAN_GROUP, 1, 1}},
        {"frame_step", {GLC_FRAME_STEP_GROUP, 1, 1}},
        {"node_pull", {1, 1, 1}}, // one node: Engine::setPull
    };
    std::size_t checked = 0;
    for (const gl::ComputeProgram& program : allPrograms()) {
        std::array<GLint, 3> size{};
        glGetProgramiv(program.name(), GL_COMPUTE_WORK_GROUP_SIZE, size.data());
        const auto it = expected.find(program.shaderName());
        // Every other shader is one invocation per item in groups of GLC_WORKGROUP_SIZE.
        const std::array<GLint, 3> want =
            it != expected.end() ? it->second : std::array<GLint, 3>{GLC_WORKGROUP_SIZE, 1, 1};
        EXPECT_EQ(size, want) << program.shaderName();
        checked += it != expected.end() ? 1 : 0;
    }
    EXPECT_EQ(checked, expected.size()) << "a shader named here is not embedded";
}

TEST(LayoutGl, HealthStructMatchesCpp) {
    gl::ComputeProgram program("node_update", {"GLC_CHECK_FINITE"});
    const GLuint p = program.name();
    EXPECT_EQ(resourceProperty(p, GL_SHADER_STORAGE_BLOCK, "HealthBuf", GL_BUFFER_BINDING), GLC_BIND_HEALTH);
    EXPECT_EQ(resourceProperty(p, GL_BUFFER_VARIABLE, "g_health.firstBadNode", GL_OFFSET),
              static_cast<GLint>(offsetof(gpu::GpuHealth, firstBadNode)));
    EXPECT_EQ(resourceProperty(p, GL_BUFFER_VARIABLE, "g_health.badSubstep", GL_OFFSET),
              static_cast<GLint>(offsetof(gpu::GpuHealth, badSubstep)));
}

TEST(LayoutGl, CompileErrorsNameTheFileAndLine) {
    // Defining u_friction as a macro turns its declaration into a syntax error on a known line of
    // common/advance_node.glsl, which node_update.comp includes; the mapped log must name that file
    // and line, not "0:<n>".
    std::ifstream in(std::string(GLCOLLIDE_SOURCE_DIR) + "/shaders/common/advance_node.glsl");
    std::string line;
    int lineNumber = 0, declaration = 0;
    while (std::getline(in, line) && declaration == 0) {
        ++lineNumber;
        if (line.find("uniform float u_friction;") != std::string::npos) declaration = lineNumber;
    }
    ASSERT_GT(declaration, 0);
    test::ExpectGlErrors expected; // Mesa also reports the compile error through KHR_debug
    try {
        gl::ComputeProgram program("node_update", {"GLC_GROUND", "u_friction 1.0 +"});
        FAIL() << "compiling broken GLSL succeeded";
    } catch (const Error& e) {
        const std::string where = "shaders/common/advance_node.glsl:" + std::to_string(declaration);
        EXPECT_NE(std::string(e.what()).find(where), std::string::npos) << e.what();
    }
}

} // namespace
} // namespace glcollide
