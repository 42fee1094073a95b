// The contact's summary: slots (sum of p, patches with p > 0, largest p).
#version 450
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 256) in;
#define SLOTS 3u
#define MAX_SLOTS 4u
#define PARTIALS_BINDING 1
#include "chunks.glsl"
#include "patch_sets.glsl"
#include "reduce.glsl"
FIELD_IN(0, p)
layout(push_constant) uniform Push { uint n; } pc;

void main()
{
    double v[SLOTS] = double[SLOTS](0.0lf, 0.0lf, 0.0lf);
    for (uint i = gl_GlobalInvocationID.x; i < pc.n; i += grid_stride())
        if (p_at(i) > 0.0lf) {
            v[0] += p_at(i);
            v[1] += 1.0lf;
            v[2] = max(v[2], p_at(i));
        }
    reduce_workgroup(v);
}
