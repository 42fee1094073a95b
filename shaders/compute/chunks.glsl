// Fields split into chunks (src/gpu/vulkan.h, gpu_buffer): a field binding is an array of
// MAX_CHUNKS storage buffers of CHUNK_DOUBLES doubles each (the device-wide chunk size, a
// specialization constant), element i in chunk i / CHUNK_DOUBLES. Each chunk is selected by a
// constant index: lavapipe offers no non-uniform indexing of buffer arrays, and neighbouring
// invocations may read different chunks. Declare a field with FIELD_IN (read), FIELD_OUT (write)
// or FIELD (both) and read it as name_at(i), write it with name_put(i, value).
#define MAX_CHUNKS 5
layout(constant_id = 0) const uint CHUNK_DOUBLES = 268435456u;

#define CHUNK_SWITCH(name, i, action)                                                                  \
    switch ((i) / CHUNK_DOUBLES) {                                                                     \
    case 0u: action(name##_chunks[0].v[(i) % CHUNK_DOUBLES]); break;                                   \
    case 1u: action(name##_chunks[1].v[(i) % CHUNK_DOUBLES]); break;                                   \
    case 2u: action(name##_chunks[2].v[(i) % CHUNK_DOUBLES]); break;                                   \
    case 3u: action(name##_chunks[3].v[(i) % CHUNK_DOUBLES]); break;                                   \
    default: action(name##_chunks[4].v[(i) % CHUNK_DOUBLES]); break;                                   \
    }
#define CHUNK_READ(element) return element
#define CHUNK_WRITE(element) element = value

#define FIELD_BLOCK(slot, access, name)                                                             \
    layout(std430, set = 0, binding = slot) access buffer name##_block { double v[]; }             \
    name##_chunks[MAX_CHUNKS];
#define FIELD_READER(name)                                                                             \
    double name##_at(uint i) { CHUNK_SWITCH(name, i, CHUNK_READ) }
#define FIELD_WRITER(name)                                                                             \
    void name##_put(uint i, double value) { CHUNK_SWITCH(name, i, CHUNK_WRITE) }

#define FIELD_IN(slot, name) FIELD_BLOCK(slot, readonly, name) FIELD_READER(name)
#define FIELD_OUT(slot, name) FIELD_BLOCK(slot, writeonly, name) FIELD_WRITER(name)
#define FIELD(slot, name) FIELD_BLOCK(slot, , name) FIELD_READER(name) FIELD_WRITER(name)
