// p = min(p scale, cap) on the elastic patches: slot (1 if any reached the cap).
#version 450
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 256) in;
#define SLOTS 1u
#define MAX_SLOTS 1u
#define PARTIALS_BINDING 1
#include "chunks.glsl"
#include "patch_sets.glsl"
#include "reduce.glsl"
FIELD(0, p)
layout(push_constant) uniform Push { double scale; double cap; uint n; } pc;

void main()
{
    double v[SLOTS] = double[SLOTS](0.0lf);
    for (uint i = gl_GlobalInvocationID.x; i < pc.n; i += grid_stride())
        if (elastic(p_at(i), pc.cap)) {
            p_put(i, project(p_at(i) * pc.scale, pc.cap));
            if (p_at(i) == pc.cap)
                v[0] = 1.0lf;
        }
    reduce_workgroup(v);
}
