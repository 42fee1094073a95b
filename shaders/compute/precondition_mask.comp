// The preconditioner's input: z = g on the step's set, 0 elsewhere.
#version 450
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 256) in;
#include "chunks.glsl"
#include "patch_sets.glsl"
FIELD_IN(0, p)
FIELD_IN(1, g)
FIELD_OUT(2, z)
layout(push_constant) uniform Push { uint n; uint join; } pc;

void main()
{
    for (uint i = gl_GlobalInvocationID.x; i < pc.n; i += grid_stride())
        z_put(i, in_preconditioned_step(p_at(i), g_at(i), pc.join) ? g_at(i) : 0.0lf);
}
