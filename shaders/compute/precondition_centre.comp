// z -= mean on the step's set: slot (<g, z> there).
#version 450
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 256) in;
#define SLOTS 1u
#define MAX_SLOTS 0u
#define PARTIALS_BINDING 3
#include "patch_sets.glsl"
#include "reduce.glsl"
layout(std430, set = 0, binding = 0) readonly buffer Pressure { double p[]; };
layout(std430, set = 0, binding = 1) readonly buffer Gap { double g[]; };
layout(std430, set = 0, binding = 2) buffer Preconditioned { double z[]; };
layout(push_constant) uniform Push { double mean; uint n; uint join; } pc;

void main()
{
    double v[SLOTS] = double[SLOTS](0.0lf);
    for (uint i = gl_GlobalInvocationID.x; i < pc.n; i += grid_stride())
        if (in_preconditioned_step(p[i], g[i], pc.join)) {
            z[i] -= pc.mean;
            v[0] += g[i] * z[i];
        }
    reduce_workgroup(v);
}
