// glcollide shared data layout: compiled both as GLSL (std430 buffers) and as C++
// (src/gl/layout.hpp includes it inside a namespace with glm aliases).
// Rules (DESIGN.md): members only float int uint vec4 ivec4 uvec4 mat4; no vec3; bindings as
// #define; vec4 members first so std430 and C++ offsets agree. C++ static_asserts every
// size and offset, and layout_gl_test compares them with what the driver reports.

// Binding points. 0-11 follow the SSBO table of the AABB-octree paper (seeds/002, Table 1);
// later capabilities take numbers from 12 on.
#define GLC_BIND_NODE_POSITIONS 0      // vec4[]: xyz position (m), w inverse mass (1/kg; 0 = pinned)
#define GLC_BIND_NODE_VELOCITIES 1     // vec4[]: xyz velocity (m/s), w unused
#define GLC_BIND_SPRINGS 2             // GpuSpring[]
#define GLC_BIND_NODE_FORCES 3         // vec4[]: xyz force (N), w unused
#define GLC_BIND_FACES 7               // uint[3*faces]: node indices, CCW seen from outside (drawable as GL_ELEMENT_ARRAY_BUFFER)
#define GLC_BIND_OBJECTS 8             // GpuObject[]
#define GLC_BIND_NODE_SPRING_OFFSETS 12 // uint[nodes+1]: CSR row offsets into node-spring list
#define GLC_BIND_NODE_SPRING_LIST 13   // uint[2*springs]: spring indices adjacent to each node
#define GLC_BIND_NODE_FACE_OFFSETS 14  // uint[nodes+1]: CSR row offsets into node-face list
#define GLC_BIND_NODE_FACE_LIST 15     // uint[3*faces]: face indices adjacent to each node

// Work-group size of the per-node and per-spring passes.
#define GLC_WORKGROUP_SIZE 128

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
    uint pad0;
    uint pad1;
};
