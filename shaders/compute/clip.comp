// p = min(p, cap).
#version 450
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 256) in;
#include "patch_sets.glsl"
layout(std430, set = 0, binding = 0) buffer Pressure { double p[]; };
layout(push_constant) uniform Push { double cap; uint n; } pc;

void main()
{
    for (uint i = gl_GlobalInvocationID.x; i < pc.n; i += grid_stride())
        p[i] = project(p[i], pc.cap);
}
