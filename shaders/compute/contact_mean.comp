// The mean of u + g0 over the elastic patches: slots (sum, count).
#version 450
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 256) in;
#define SLOTS 2u
#define MAX_SLOTS 0u
#define PARTIALS_BINDING 3
#include "chunks.glsl"
#include "patch_sets.glsl"
#include "reduce.glsl"
FIELD_IN(0, p)
FIELD_IN(1, u)
FIELD_IN(2, g0)
layout(push_constant) uniform Push { double cap; uint n; } pc;

void main()
{
    double v[SLOTS] = double[SLOTS](0.0lf, 0.0lf);
    for (uint i = gl_GlobalInvocationID.x; i < pc.n; i += grid_stride())
        if (elastic(p_at(i), pc.cap)) {
            v[0] += u_at(i) + g0_at(i);
            v[1] += 1.0lf;
        }
    reduce_workgroup(v);
}
