// The preconditioner's input: z = g on the step's set, 0 elsewhere.
#version 450
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 256) in;
#include "patch_sets.glsl"
layout(std430, set = 0, binding = 0) readonly buffer Pressure { double p[]; };
layout(std430, set = 0, binding = 1) readonly buffer Gap { double g[]; };
layout(std430, set = 0, binding = 2) writeonly buffer Preconditioned { double z[]; };
layout(push_constant) uniform Push { uint n; uint join; } pc;

void main()
{
    for (uint i = gl_GlobalInvocationID.x; i < pc.n; i += grid_stride())
        z[i] = in_preconditioned_step(p[i], g[i], pc.join) ? g[i] : 0.0lf;
}
