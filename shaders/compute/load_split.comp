// The loads delta^2 sum p over the elastic patches and over the others: slots (elastic, capped).
#version 450
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 256) in;
#define SLOTS 2u
#define MAX_SLOTS 0u
#define PARTIALS_BINDING 1
#include "chunks.glsl"
#include "patch_sets.glsl"
#include "reduce.glsl"
FIELD_IN(0, p)
layout(push_constant) uniform Push { double cap; double d2; uint n; } pc;

void main()
{
    double v[SLOTS] = double[SLOTS](0.0lf, 0.0lf);
    for (uint i = gl_GlobalInvocationID.x; i < pc.n; i += grid_stride()) {
        if (elastic(p_at(i), pc.cap))
            v[0] += p_at(i) * pc.d2;
        else
            v[1] += p_at(i) * pc.d2;
    }
    reduce_workgroup(v);
}
