// u += K (the recorded changes) by direct summation: u_i += sum_k c_k K(|x_i - x_k|, |y_i - y_k|),
// the changes taken in ascending patch order (each workgroup sorts the list in shared memory: the
// append order is the atomics', and the sum's order must not depend on it), as the CPU engine adds them.
#version 450
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 256) in;
#include "chunks.glsl"
#include "patch_sets.glsl"
#include "point_loads.glsl"
FIELD(0, u)
FIELD_IN(1, kernel)
layout(std430, set = 0, binding = 2) readonly buffer ChangeIndex { uint change_index[]; };
layout(std430, set = 0, binding = 3) readonly buffer ChangeValue { double change_value[]; };
layout(push_constant) uniform Push { uint nx; uint ny; uint count; } pc;

shared uint sorted_x[CHANGE_CAPACITY];
shared uint sorted_y[CHANGE_CAPACITY];
shared double sorted_value[CHANGE_CAPACITY];

// Entry t goes to its rank among the patch indices (distinct: one change per patch).
void sort_changes()
{
    for (uint t = gl_LocalInvocationID.x; t < pc.count; t += gl_WorkGroupSize.x) {
        uint index = change_index[t], rank = 0u;
        for (uint j = 0u; j < pc.count; ++j)
            rank += change_index[j] < index ? 1u : 0u;
        sorted_x[rank] = index % pc.nx;
        sorted_y[rank] = index / pc.nx;
        sorted_value[rank] = change_value[t];
    }
    barrier();
}

uint offset(uint a, uint b) { return a > b ? a - b : b - a; }

void main()
{
    sort_changes();
    uint n = pc.nx * pc.ny;
    for (uint i = gl_GlobalInvocationID.x; i < n; i += grid_stride()) {
        uint ix = i % pc.nx, iy = i / pc.nx;
        double sum = u_at(i);
        for (uint k = 0u; k < pc.count; ++k)
            sum += sorted_value[k] * kernel_at(offset(iy, sorted_y[k]) * pc.nx + offset(ix, sorted_x[k]));
        u_put(i, sum);
    }
}
