// The collision pipeline's append lists (GLC_LIST_* of layout.glsl): one counter array, so every
// kernel appends and bounds its loops the same way. Include after layout.glsl.
layout(std430, binding = GLC_BIND_COLLISION_COUNTERS) coherent buffer CollisionCountersBuf { GpuCollisionCounters g_counters; };

// Appends `item` to `items`, the storage of list `list`: the count stays exact even when the list
// is full, so the host can grow the list and rerun the stage (lists never drop data).
#define GLC_APPEND(list, items, item) { uint slot_ = atomicAdd(g_counters.lists[list].count, 1u); if (slot_ < g_counters.lists[list].capacity) items[slot_] = item; }

// Entries of list `list` that were stored (the count may exceed the capacity on overflow).
uint storedCount(uint list) { return min(g_counters.lists[list].count, g_counters.lists[list].capacity); }

// Reserves `n` consecutive slots of list `list` with one atomic and returns the first; the caller
// stores item j at slot + j only if slot + j < g_counters.lists[list].capacity (the count stays
// exact, as with GLC_APPEND).
uint glcReserve(uint list, uint n) { return atomicAdd(g_counters.lists[list].count, n); }
