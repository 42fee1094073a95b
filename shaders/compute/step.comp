// The step length's sums over the step's set, K t read from the transform grid:
// slots (<g, t>, <K t, t>, sum K t, sum t, count).
#version 450
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 256) in;
#define SLOTS 5u
#define MAX_SLOTS 0u
#define PARTIALS_BINDING 4
#include "patch_sets.glsl"
#include "reduce.glsl"
layout(std430, set = 0, binding = 0) readonly buffer Pressure { double p[]; };
layout(std430, set = 0, binding = 1) readonly buffer Gap { double g[]; };
layout(std430, set = 0, binding = 2) readonly buffer Direction { double t[]; };
layout(std430, set = 0, binding = 3) readonly buffer Real { double real_grid[]; };
layout(push_constant) uniform Push { double cap; uint nx; uint ny; uint px; uint join; } pc;

void main()
{
    double v[SLOTS] = double[SLOTS](0.0lf, 0.0lf, 0.0lf, 0.0lf, 0.0lf);
    uint n = pc.nx * pc.ny;
    for (uint i = gl_GlobalInvocationID.x; i < n; i += grid_stride())
        if (in_step(p[i], g[i], pc.cap, pc.join)) {
            double q = real_grid[(i / pc.nx) * pc.px + i % pc.nx];
            v[0] += g[i] * t[i];
            v[1] += q * t[i];
            v[2] += q;
            v[3] += t[i];
            v[4] += 1.0lf;
        }
    reduce_workgroup(v);
}
