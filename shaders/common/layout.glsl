// glcollide shared data layout: compiled both as GLSL (std430 buffers) and as C++
// (src/core/gpu_layout.hpp includes it inside a namespace with glm aliases).
// Rules (docs/design/decisions/0001-ssbo-layout-shared-by-glsl-and-cpp.md): members only float int uint vec4 ivec4 uvec4 mat4; no vec3; bindings as
// #define; vec4 members first so std430 and C++ offsets agree. C++ static_asserts every
// size and offset, and layout_gl_test compares them with what the driver reports.

// Binding points. 0-11 follow the SSBO table of the AABB-octree paper (seeds/002, Table 1);
// later capabilities take numbers from 12 on.
#define GLC_BIND_NODE_POSITIONS 0      // vec4[]: xyz position (m), w inverse mass (1/kg; 0 = pinned)
#define GLC_BIND_NODE_VELOCITIES 1     // vec4[]: xyz velocity (m/s), w unused
#define GLC_BIND_SPRINGS 2             // GpuSpring[]
#define GLC_BIND_NODE_FORCES 3         // vec4[]: xyz force (N), w unused
#define GLC_BIND_BOXES 4               // GpuBox[objects * 8^depth]: AABB-octree leaf boxes, refit each substep
#define GLC_BIND_INTERSECTIONS 5       // uvec2[capacity]: face pairs whose closed triangles intersect (TriTri output)
#define GLC_BIND_FACE_INFO 6           // GpuFaceInfo[faces] (the paper's slot 6 held face normals; we compute those on the fly)
#define GLC_BIND_FACES 7               // uint[3*faces]: node indices, CCW seen from outside (drawable as GL_ELEMENT_ARRAY_BUFFER)
#define GLC_BIND_OBJECTS 8             // GpuObject[]
#define GLC_BIND_BOX_FACE_LIST 9       // uint[faces]: face indices grouped by leaf box (CSR items)
#define GLC_BIND_FACE_PAIRS 10         // uvec2[capacity]: candidate face pairs (broad-phase output)
#define GLC_BIND_BOX_MASK 11           // uint[boxes * boxes]: 1 where two leaf boxes overlap (masked broad phase)
#define GLC_BIND_NODE_SPRING_OFFSETS 12 // uint[nodes+1]: CSR row offsets into node-spring list
#define GLC_BIND_NODE_SPRING_LIST 13   // uint[2*springs]: spring indices adjacent to each node
#define GLC_BIND_NODE_FACE_OFFSETS 14  // uint[nodes+1]: CSR row offsets into node-face list
#define GLC_BIND_NODE_FACE_LIST 15     // uint[3*faces]: face indices adjacent to each node
#define GLC_BIND_BOX_FACE_OFFSETS 16   // uint[boxes+1]: CSR row offsets into the box face list
#define GLC_BIND_BOX_PAIRS 17          // uvec2[capacity]: overlapping leaf-box pairs (octree broad phase)
#define GLC_BIND_COLLISION_COUNTERS 18 // GpuCollisionCounters: (count, capacity) of every list, statistics
#define GLC_BIND_CONTACT_FORCES 19     // ivec4[nodes]: contact force, fixed point (GLC_CONTACT_FORCE_SCALE units per N)
#define GLC_BIND_DISPATCH_ARGS 20      // uint[3 * GLC_LIST_COUNT]: indirect dispatch arguments per list, written on the GPU
#define GLC_BIND_QUERY_TRIANGLES 21   // float[18 * pairs]: tri-tri query input, a0 a1 a2 b0 b1 b2 (xyz each)
#define GLC_BIND_QUERY_RESULTS 22     // uint[pairs]: tri-tri query output, 1 = the closed triangles intersect
#define GLC_BIND_QUERY_STATS 23       // uint[3]: tri-tri query (robust): exact fallbacks, undecided pairs,
                                      // pairs the exact pass could not finish (an error)
// CCD queries (src/passes/ccd_query_pass.cpp) take the tri-tri query slots: a query batch runs alone.
#define GLC_BIND_CCD_QUERIES GLC_BIND_QUERY_TRIANGLES // float[25 * queries]: 8 points xyz (4 at t = 0, the same 4 at t = 1), minimum separation
#define GLC_BIND_CCD_RESULTS GLC_BIND_QUERY_RESULTS   // uint[3 * queries]: bit 0 may collide, bit 1 capped; time of impact (float bits); boxes evaluated
#define GLC_BIND_HEALTH 24             // GpuHealth: the first non-finite node NodeUpdate produced
#define GLC_BIND_UNDECIDED 25          // uint[]: robust TriTri: items the filtered pass left to the exact pass
                                       // (candidate indices; query: pair indices)
// The linear BVH broad phase (docs/design/decisions/0017-gpu-linear-bvh.md). Node n < faces-1 is
// internal node n, node faces-1+i is the leaf of the i-th face in Morton order; node 0 is the root.
#define GLC_BIND_BVH_BOXES 26          // GpuBox[2*faces-1]: node boxes (leaves: inflated face boxes), refit each substep
#define GLC_BIND_BVH_LINKS 27          // uvec4[2*faces-1]: (left child | leaf: face, right child | leaf: sorted index, parent, escape)
#define GLC_BIND_BVH_VISITS 28         // uint[faces-1]: refit arrival counters, 0 between refits
#define GLC_BIND_BVH_RESUME 29         // uint[faces]: traversal: the next node of each query, GLC_BVH_NONE when done
#define GLC_BIND_SORT_KEYS_IN 30       // uint[]: radix sort pass input keys (Morton codes)
#define GLC_BIND_SORT_VALUES_IN 31     // uint[]: radix sort pass input values (face indices)
#define GLC_BIND_SORT_KEYS_OUT 32      // uint[]: radix sort pass output keys
#define GLC_BIND_SORT_VALUES_OUT 33    // uint[]: radix sort pass output values
#define GLC_BIND_SORT_BLOCK_COUNTS 34  // uint[16 * blocks]: per-block digit counts, scanned to offsets in place
#define GLC_BIND_BVH_BOUNDS 35         // uvec4[2]: bounds of the face-box centroids as order-preserving uints
// Representative-Triangle feature pairs (docs/design/decisions/0018-representative-triangles.md).
#define GLC_BIND_VERTEX_FACE_PAIRS 36  // uvec2[capacity]: (node, face): a vertex against a face
#define GLC_BIND_EDGE_EDGE_PAIRS 37    // uvec2[capacity]: (3*face+edge, 3*face+edge): two edges, edge e from corner e to e+1
// The implicit Euler solver (docs/integration.md): block-Jacobi preconditioned conjugate
// gradients on A·Δv = b, one vec4 per node per vector (w unused).
#define GLC_BIND_SOLVER_RESIDUAL 38       // vec4[nodes]: r = b − A·Δv
#define GLC_BIND_SOLVER_PRECONDITIONED 39 // vec4[nodes]: z = P⁻¹·r (P: the 3x3 diagonal blocks of A)
#define GLC_BIND_SOLVER_DIRECTION_IN 40   // vec4[nodes]: the previous search direction p
#define GLC_BIND_SOLVER_DIRECTION_OUT 41  // vec4[nodes]: the new search direction p = z + beta·p
#define GLC_BIND_SOLVER_PRODUCT 42        // vec4[nodes]: q = A·p
#define GLC_BIND_SOLVER_BLOCK_INVERSE 43  // float[6*nodes]: P⁻¹ per node, symmetric: xx xy xz yy yz zz
#define GLC_BIND_SOLVER_PARTIALS_R 44     // vec2[groups]: per work group (r·z, r·r)
#define GLC_BIND_SOLVER_PARTIALS_PQ 45    // float[groups]: per work group p·q
#define GLC_BIND_SOLVER_STATE 46          // GpuSolverState
#define GLC_BIND_HEAVY_NODES 47           // uint[]: nodes with more than GLC_HEAVY_ROW springs, ascending
// Continuous collision detection (docs/ccd.md, "In the engine").
#define GLC_BIND_PREDICTED_POSITIONS 48   // vec4[nodes]: x1, where the integrator puts the node at the end of
                                          // the substep (NodePredict); w inverse mass. x0 is binding 0.
#define GLC_BIND_NODE_TOI 49              // uint[nodes]: bits of the node's earliest time of impact in the
                                          // substep, in [0, 1] (non-negative floats order like their bits:
                                          // atomicMin); +inf bits when none
// Contacts inside the implicit solve (docs/integration.md, "Contacts in the implicit solve"). One
// buffer (the solver's kernels are at GL's minimum of 16 storage blocks with every feature on):
// words [0, nodes]: CSR row offsets into the entries; then 4 words per record slot: the node →
// contact incidence entries (4·slot + corner, each row sorted by the pair's key); then the records,
// GpuImplicitContact (12 words) per slot of the vertex-face list, then per slot of the edge-edge list.
#define GLC_BIND_IMPLICIT_CONTACTS 50       // uint[nodes + 1 + 16 · (vertex-face + edge-edge capacity)]
#define GLC_BIND_NODE_CONTACT_COUNTS 51     // uint[nodes]: incidences per node (integer atomics), then scatter cursors
#define GLC_BIND_OBJECT_TOI 52            // uint[objects]: the earliest time of impact of the object's nodes
                                          // (SafeStep, decision 0024), bits as GLC_BIND_NODE_TOI
#define GLC_BIND_FEATURE_ORPHANS 53       // uint[faces + 1 + 2 * entries]: the orphan feature pairs each face pair
                                          // carries (model::orphanTable; FeaturePairs, continuous detection)
#define GLC_ORPHAN_HIGHER_CORNERS 3u      // an entry's bits: 1 << k, corner k of the lower face against the
#define GLC_ORPHAN_EDGE_PAIRS 6u          // higher; << (3 + k), corner k of the higher; << (6 + 3e + g), edge e
                                          // of the lower face against edge g of the higher
#define GLC_BIND_TANGLED 54               // uint[nodes + faces]: 1 for the nodes, then the faces, of the face pairs
                                          // that intersect at x0 (the safe step's CCD leaves their pairs out)
#define GLC_BIND_ENERGY_GUARD 55          // GpuEnergyGuard: the energy guard's sums and counts (decision 0024)
// Radial view-based culling's classification (RadialClassify, docs/culling.md).
#define GLC_BIND_RADIAL_OBSERVERS 56      // vec4[2 * observers]: each observer's position at t = 0, then at t = 1
#define GLC_BIND_RADIAL_FACE_OBSERVER 57  // uint[faces]: the face's observer, or GLC_RADIAL_NO_OBSERVER
#define GLC_BIND_RADIAL_POSITIVE 58       // uint[(faces + 31) / 32]: bit f % 32 of word f / 32 set when face f
                                          // is proven positive for its observer over the substep
#define GLC_BIND_RADIAL_OBSERVER_NODES 59 // uvec4[5 · observers]: the first node and node count whose centroid is the
                                          // observer (RadialObservers; 0 nodes: a cluster's, which
                                          // RadialGhostNodes sets back behind its outer loop), 1 when the
                                          // surface's faces wind inward (classified the other way round), 1
                                          // for a user observer point, 2 for a user segment: then the next
                                          // uvec4 holds the four frame nodes of the point (the segment's
                                          // first end) and the one after the bits of their weights, and
                                          // for a segment the next two its second end's
#define GLC_BIND_RADIAL_CONES 60          // vec4[faces]: each observed face's footprint cone (unit axis, cosine)
#define GLC_BIND_RADIAL_NONPOSITIVE 61    // uint[1 + 2 * observers + faces]: the observed faces not proven positive:
                                          // their count, then per observer its count and where its bucket
                                          // starts (from the buffer's start), then the buckets (one slot per
                                          // classified face of the observer)
#define GLC_BIND_RADIAL_FREE 62           // uint[1 + (faces + 31) / 32]: word 0 is 1 when the mask holds for this
                                          // substep; bit f % 32 of word 1 + f / 32 set when face f is free
                                          // (intersects nothing of its observer's surface during the substep)
#define GLC_BIND_RADIAL_MOVED 63          // uint: set to 1 when a node's position differs from the last substep's
                                          // committed end (the host moved it between frames; RadialHostCheck)
#define GLC_BIND_CCD_VERTEX_FACE_TESTS 64 // uint[]: GLC_LIST_CCD_VERTEX_FACE_TESTS
#define GLC_BIND_CCD_EDGE_EDGE_TESTS 65   // uint[]: GLC_LIST_CCD_EDGE_EDGE_TESTS
// Ghost triangles of radial culling (docs/culling.md, "Ghost triangles"): classified faces past the
// real ones. A classified face f >= the real face count is ghost face f - real faces; a node index
// >= the node count is ghost node index - nodes.
#define GLC_BIND_RADIAL_GHOST_FACES 66     // uint[3 * ghost faces]: each ghost face's three node indices
#define GLC_BIND_RADIAL_GHOST_LOOPS 67     // uint[8 * ghost nodes + loop nodes]: per ghost node (where its loop's
                                           // nodes are listed, from the buffer's start; how many; its kind,
                                           // GLC_GHOST_*; the node a skirt node hangs behind), (its depth's
                                           // float bits; the observer it places or GLC_RADIAL_NO_OBSERVER;
                                           // that observer's depth's bits; unused); then the loop nodes
#define GLC_GHOST_LOOP_MEAN 0u             // the mean of its loop (model::GhostKind::LoopMean)
#define GLC_GHOST_APEX 1u                  // mean - depth * radius * axis of its loop (a cluster's apex)
#define GLC_GHOST_SKIRT 2u                 // its node - depth * radius * axis of its loop (a cluster's skirt)
#define GLC_BIND_RADIAL_GHOST_POSITIONS 68 // vec4[2 * ghost nodes]: each ghost node at t = 0, then at t = 1
                                           // (the mean of its loop's nodes; RadialGhostNodes)
#define GLC_BIND_RADIAL_WINDING 70         // uint[2 * observers]: per observer the crossings of a ray from it at x0
                                           // with its surface (a two's complement sum: its winding number)
                                           // and 1 when a crossing was not proven (RadialWinding)
#define GLC_BIND_RADIAL_NODE_OBSERVER 71   // uint[nodes]: the observer of every face around the node, or
                                           // GLC_RADIAL_NO_OBSERVER (vertex-face pairs: the vertex on the surface)
#define GLC_RADIAL_NO_OBSERVER 0xffffffffu
// The Newton steps' line search (NewtonLineSearch, decision 0024 "Line search").
#define GLC_BIND_LINE_SEARCH 73            // GpuLineSearch: the last sum of the incremental potential
#define GLC_BIND_LINE_SEARCH_VELOCITIES 74 // vec4[3 * nodes]: v0 (the substep's start), the Newton step's
                                           // start, its full step's end
// Recovery from intersections deeper than the thickness (Untangle, decision 0024 "Deep intersections").
#define GLC_BIND_UNTANGLE_PUSH 69          // ivec4[nodes]: the sum of a node's pushes in fixed point
                                           // (u_pushScale units per unit push) in xyz; w unused (alignment)
#define GLC_BIND_UNTANGLE_COUNTS 72        // uint[2]: nodes moved, intersecting pairs without two piercings
// Segment observers of radial culling (decision 0025, "Segment observers").
#define GLC_BIND_RADIAL_SEGMENTS 75        // vec4[2 * observers]: a segment observer's second end at t = 0, then
                                           // at t = 1 (its first end: GLC_BIND_RADIAL_OBSERVERS), w = 1;
                                           // w = 0 for a point observer
#define GLC_BIND_RADIAL_FEET 76            // vec2[classified faces]: the interval of u in [0, 1] that the feet of
                                           // a face's points on its segment observer lie in ([0, 1] for a point
                                           // observer, or a cone of every direction)
#define GLC_BIND_RADIAL_CELLS 77           // uint[GLC_RADIAL_CELL_WORDS * observers]: the footprint cells marked by
                                           // faces not proven positive (common/radial_cells.glsl)
// Restitution at any step (GroundImpact, ContactImpact; decision 0024 "Restitution at any step").
#define GLC_BIND_START_VELOCITIES 78       // vec4[nodes]: every node's velocity at the start of the substep
#define GLC_BIND_IMPACT_IMPULSES 79        // float[vertex-face + edge-edge list slots]: ContactImpact's
                                           // accumulated normal impulse of each pair (N over the substep)
#define GLC_RADIAL_CELL_GRID 16            // fine cells per axis of direction space [-1, 1]^3 (a multiple of 4)
#define GLC_RADIAL_COARSE_GRID 4           // coarse cells per axis (a multiple of 4), for wide footprints
#define GLC_RADIAL_FOOT_BINS 8             // bins of a segment's feet [0, 1]: a byte per cell
#define GLC_RADIAL_COARSE_WORDS 16         // GLC_RADIAL_COARSE_GRID^3 * GLC_RADIAL_FOOT_BINS / 32
#define GLC_RADIAL_CELL_WORDS 1040         // per observer: the coarse words, then GLC_RADIAL_CELL_GRID^3 / 4

// One more than the highest binding above: the engine uses bindings 0 .. GLC_BINDING_COUNT-1, the
// host-state guard saves and restores exactly those, and start-up refuses a device with fewer
// GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS. tests/gl/layout_gl_test.cpp checks that every block of
// every kernel lies below it. Add a binding above, then raise this.
#define GLC_BINDING_COUNT 80

// Bits of GpuFaceInfo.owned: the face that "owns" a vertex or an edge (the lowest-indexed face
// containing it) is the only one that generates its vertex-face and edge-edge contacts, so a
// feature shared by several faces is never counted twice.
#define GLC_OWN_VERTEX0 1u
#define GLC_OWN_VERTEX1 2u
#define GLC_OWN_VERTEX2 4u
#define GLC_OWN_EDGE01 8u
#define GLC_OWN_EDGE12 16u
#define GLC_OWN_EDGE20 32u

// Bits of u_pairRules (collision.glsl): which face pairs may collide.
#define GLC_RULE_BETWEEN_OBJECTS 1u // faces of different objects (effect `collisions`)
#define GLC_RULE_SELF 2u            // faces of one object that share no node (effect `self_collisions`)

// Work-group sizes, shared by the shaders (local_size) and the C++ that sizes their dispatches;
// tests/gl/layout_gl_test.cpp checks each program's GL_COMPUTE_WORK_GROUP_SIZE against them.
#define GLC_WORKGROUP_SIZE 128   // one invocation per item: nodes, springs, list entries
#define GLC_BB_UPDATE_GROUP 64   // BBUpdate: one group per leaf box
#define GLC_BOX_PAIR_TILE 8      // box-pair kernels: 8 x 8 tiles of the boxes x boxes grid
#define GLC_FACE_PAIR_TILE 16    // face-pair kernels: 16 x 16 tiles of the faces x faces grid
#define GLC_EXPAND_GROUP 64      // octree expansion: one group (x z slices) per box pair
#define GLC_SORT_BLOCK 256       // radix sort: items per work group (one per invocation)
#define GLC_SORT_DIGIT_BITS 4    // radix sort: bits per pass (16 digits)
#define GLC_SCAN_GROUP 256       // radix sort: the one work group that scans the block counts
#define GLC_FRAME_STEP_GROUP 1024 // FrameStep: the one work group that runs a small scene's whole frame

// A node with more springs than this is gathered by a whole work group of GLC_WORKGROUP_SIZE
// invocations (one per GLC_WORKGROUP_SIZE springs each), so no invocation walks more than this many
// springs while the others of its group wait (docs/integration.md, "No serial hot spots").
#define GLC_HEAVY_ROW 64u

#define GLC_BVH_NONE 0xFFFFFFFFu // BVH link that points nowhere (the root's parent, the last escape)

// Append lists of the collision pipeline: the index of each list's (count, capacity) in
// GpuCollisionCounters.lists and of its indirect dispatch arguments (GLC_BIND_DISPATCH_ARGS).
#define GLC_LIST_BOX_PAIRS 0u     // uvec2 overlapping leaf-box pairs (octree broad phase)
#define GLC_LIST_CANDIDATES 1u    // uvec2 candidate face pairs (every broad phase)
#define GLC_LIST_UNDECIDED 2u     // uint candidate indices the filtered TriTri left to the exact pass
#define GLC_LIST_INTERSECTIONS 3u // uvec2 face pairs whose closed triangles intersect
#define GLC_LIST_VERTEX_FACE 4u   // uvec2 (node, face) feature pairs of the candidates (R-Triangles)
#define GLC_LIST_EDGE_EDGE 5u     // uvec2 (edge, edge) feature pairs of the candidates (R-Triangles)
#define GLC_LIST_CCD_VERTEX_FACE_TESTS 6u // uint indices into GLC_LIST_VERTEX_FACE the CCD tests (CcdFilter, radial culling)
#define GLC_LIST_CCD_EDGE_EDGE_TESTS 7u   // uint indices into GLC_LIST_EDGE_EDGE the CCD tests (CcdFilter, radial culling)
#define GLC_LIST_COUNT 8

// A spring between two nodes (global node indices).
struct GpuSpring {
    uint nodeA;
    uint nodeB;
    float restLength; // m
    float stiffness;  // N/m
    float damping;    // N*s/m along the spring
    uint object;
    uint pad0;
    uint pad1;
};

// Ranges of one object in the global node, face and spring arrays.
struct GpuObject {
    uint firstNode;
    uint nodeCount;
    uint firstFace;
    uint faceCount;
    uint firstSpring;
    uint springCount;
    uint firstBox;  // first leaf box of this object (objects own 8^depth consecutive boxes)
    uint closed;    // 1 when every edge has exactly two faces (a closed surface with outward normals)
};

// An axis-aligned box; an empty box has lo > hi and overlaps nothing.
struct GpuBox {
    vec4 lo; // xyz min (m), w unused
    vec4 hi; // xyz max (m), w unused
};

// Per-face data the collision passes need beside the three node indices.
// One contact of the implicit solve (implicit_contact_find.comp): nodes n with signed weights a
// (vertex-face (1, −w0, −w1, −w2), edge-edge (1−s, s, −(1−t), −t)), unit normal u from side B to
// side A, penalty force magnitude k·depth: > 0 within the thickness, 0 for a pair within the margin
// beyond it that approaches (ContactParams::solveMargin: stiffness without force).
struct GpuImplicitContact {
    uvec4 nodes;
    vec4 weights;
    vec4 normalForce; // xyz: u; w: k·depth (N)
};

struct GpuFaceInfo {
    uint object; // index into ObjectsBuf
    uint box;    // global leaf box index
    uint owned;  // GLC_OWN_* bits
    uint pad0;
};

// One append list's counter. A writer does i = atomicAdd(count, 1) and stores only if
// i < capacity (GLC_APPEND), so after a pass `count` is the exact number of items found, even on
// overflow; the host then grows the list to at least `count` and reruns the stage that wrote it
// (docs/design/decisions/0012-append-list-and-stage-chain-written-once.md).
struct GpuListCounter {
    uint count;
    uint capacity;
};

// Statistics of the collision pipeline, by id: GpuCollisionCounters.stats[GLC_STAT_*]. Their
// names, reset values and owners (reset when detect() starts, or by the stage that writes them
// each time it runs) are in one table, passes::kCollisionStats (append_lists.cpp).
#define GLC_STAT_EXACT_FALLBACKS 0u   // robust TriTri: predicates the exact pass evaluated in integers
#define GLC_STAT_CONTACTS 1u          // vertex-face and edge-edge contacts that produced a force
#define GLC_STAT_BVH_UNFINISHED 2u    // BVH traversal: queries that used up their rounds (the stage reruns with more)
#define GLC_STAT_BVH_NODE_VISITS 3u   // BVH traversal: nodes whose box was tested (the tree-quality figure)
#define GLC_STAT_EXACT_ERRORS 4u      // robust TriTri: pairs the exact pass could not finish (glcExactFailed;
                                      // never by construction): detect() throws, no answer is used
#define GLC_STAT_CCD_VERTEX_FACE_HITS 5u // CCD: vertex-face pairs that may touch during the substep
#define GLC_STAT_CCD_EDGE_EDGE_HITS 6u   // CCD: edge-edge pairs that may touch during the substep
#define GLC_STAT_CCD_CAPPED 7u           // CCD: pairs whose refinement ran out of budget ("may touch")
#define GLC_STAT_CCD_BOXES 8u            // CCD: boxes of (t, u, v) evaluated (modulo 2^32)
#define GLC_STAT_CCD_EARLIEST_TOI 9u     // CCD: bits of the earliest time of impact of the substep (+inf: none)
#define GLC_STAT_SAFE_STEP_CUTS 10u      // SafeStep: node steps cut (summed over the substep's rounds)
#define GLC_STAT_SAFE_STEP_GROUND 11u    // SafeStep: nodes whose predicted step crossed the ground
#define GLC_STAT_CCD_TANGLED 12u         // CCD (safe step): feature pairs left out because their faces intersect at x0
#define GLC_STAT_RADIAL_CULLED_TRI_TRI 13 // radial culling: candidate face pairs TriTri left out (a face is free)
#define GLC_STAT_RADIAL_CULLED_CCD 14     // radial culling: feature pairs the CCD left out (a face is free)
#define GLC_STAT_RADIAL_NON_POSITIVE 15  // radial culling: observed faces not proven positive over the substep
#define GLC_STAT_RADIAL_FREE 16          // radial culling: free faces (positive, footprint meets no non-positive one)
#define GLC_STAT_RADIAL_VIOLATED 17      // radial culling: surfaces whose premise fails (not wound exactly once
                                         // around their observer at x0, or not proven so: RadialWinding)
#define GLC_STAT_COUNT 18

struct GpuCollisionCounters {
    GpuListCounter lists[GLC_LIST_COUNT]; // indexed by GLC_LIST_*
    uint stats[GLC_STAT_COUNT];           // indexed by GLC_STAT_*
};

// Written by NodeUpdate when a node's new position or velocity is not finite (EngineOptions::
// checkFinite). Both fields start at GLC_HEALTH_NONE and are never reset: the engine reads them
// after every frame until they are set, so the first frame that sets them is the one it reports.
// A substep records only while badSubstep >= its own index, so a later substep of the same frame
// cannot replace the first one's node.
#define GLC_HEALTH_NONE 0xFFFFFFFFu
// The implicit solver's shared scalars (written by one invocation, read by the next passes) and
// the frame's solver statistics (cleared by the engine before each frame).
#define GLC_SOLVER_RUNNING 0xFFFFFFFFu
// A pair within the implicit solve's margin counts as approaching when its relative normal velocity
// u·Σ a_i v_i is below −GLC_APPROACH_SLACK·Σ |a_i||v_i| (ContactParams::solveMargin). The weights sum
// to 0 on each side, so a pair moving rigidly approaches at exactly 0, which a float sum of four
// terms gets within a few units of 2⁻²⁴ of that scale; 2⁻¹⁶ leaves such pairs out on any GPU and
// in the double twin alike.
#define GLC_APPROACH_SLACK (1.0 / 65536.0)
struct GpuSolverState {
    float rhsNormSquared;     // ‖b‖² of this substep's system
    float rz[2];              // r·z after the iteration of that parity
    uint doneAt;              // the iteration whose residual met the tolerance, GLC_SOLVER_RUNNING before
    uint maxIterations;       // frame: most iterations any substep took
    uint maxResidualBits;     // frame: largest final ‖r‖/‖b‖ of any substep (float bits: non-negative
                              // floats order like their bits, so atomicMax picks the largest)
    uint totalIterations;     // frame: iterations summed over substeps
    uint unconvergedSubsteps; // frame: substeps that reached the iteration cap above the tolerance
};

// The energy guard (energy_guard.comp, decision 0024): the start of the substep's total energy,
// what the guard did this frame (the host clears the counts when a frame starts) and one partial
// sum per terms group: (energy, magnitude scale, kinetic energy, contact energy).
#define GLC_ENERGY_GROUPS 256 // groups of the terms dispatch; the decide group sums their partials
struct GpuEnergyGuard {
    float startTotal;     // J: the total energy at the start of the substep (the last accepted state's)
    float startMagnitude; // J: the magnitude scale of its terms (the resolution's base)
    uint hasStart;        // 0 until a total was recorded
    float scale;          // the velocity scale the last decide chose (1: none)
    float lastTotal;      // J: the last state's total (after the guard's scale when it accepted one)
    float firstTotal;     // J: the substep's first total (before any pull-back)
    uint outcome;         // the last decide: 0 accepted (maybe with a scale), 1 pull the step back
    uint acted;           // frame: substeps whose energy rose beyond the resolution
    float removed;        // J, frame: energy taken out (velocity scales and pull-backs)
    float unremoved;      // J, frame: rises left in the state (only rounding at x0 can leave any)
    float largestExcess;  // J, frame: the largest rise found
    float lastKinetic;    // J: the kinetic part of lastTotal
    float lastContact;    // J: the contacts' and the ground's penalty part of lastTotal
    uint pad0;
    uint pad1;
    uint pad2;
    vec4 partials[GLC_ENERGY_GROUPS];
    // Per group, the contacts' energy and its magnitude as exact 128-bit fixed-point sums (units of
    // 2⁻⁶⁴ J, four 32-bit words, least significant first): the feature-pair lists are filled in an
    // order that changes from run to run, and only an exact sum does not depend on it.
    uvec4 contactPartials[2 * GLC_ENERGY_GROUPS];
};

// The Newton steps' line search (newton_line_search.comp): the last candidate's incremental
// potential Φ (J) and the magnitude scale of its terms, the largest change |δ| of a free node's
// velocity, and the partial sums of its terms groups as GpuEnergyGuard's: (Φ, magnitude, unused,
// unused) and the contacts' exact sums.
struct GpuLineSearch {
    float total;         // J: Φ of the last candidate summed
    float magnitude;     // J: the magnitude scale of its terms (the resolution's base)
    uint largestChange;  // floatBitsToUint of max |δ| (m/s) over the free nodes: an atomicMax of
                         // non-negative floats' bits, which order like the floats (order-independent)
    uint pad1;
    vec4 partials[GLC_ENERGY_GROUPS];
    uvec4 contactPartials[2 * GLC_ENERGY_GROUPS];
};

struct GpuHealth {
    uint firstBadNode; // lowest global node index found non-finite in substep badSubstep
    uint badSubstep;   // index within its frame (0 .. substeps-1) of the first such substep
    uint pad0;
    uint pad1;
};
