// p = min(p, cap).
#version 450
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 256) in;
#include "chunks.glsl"
#include "patch_sets.glsl"
FIELD(0, p)
layout(push_constant) uniform Push { double cap; uint n; } pc;

void main()
{
    for (uint i = gl_GlobalInvocationID.x; i < pc.n; i += grid_stride())
        p_put(i, project(p_at(i), pc.cap));
}
