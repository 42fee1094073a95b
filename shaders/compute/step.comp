// The step length's sums over the step's set, K t read from the transform grid:
// slots (<g, t>, <K t, t>, sum K t, sum t, count).
#version 450
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 256) in;
#define SLOTS 5u
#define MAX_SLOTS 0u
#define PARTIALS_BINDING 4
#include "chunks.glsl"
#include "patch_sets.glsl"
#include "reduce.glsl"
FIELD_IN(0, p)
FIELD_IN(1, g)
FIELD_IN(2, t)
FIELD_IN(3, real_grid)
layout(push_constant) uniform Push { double cap; uint nx; uint ny; uint px; uint join; } pc;

void main()
{
    double v[SLOTS] = double[SLOTS](0.0lf, 0.0lf, 0.0lf, 0.0lf, 0.0lf);
    uint n = pc.nx * pc.ny;
    for (uint i = gl_GlobalInvocationID.x; i < n; i += grid_stride())
        if (in_step(p_at(i), g_at(i), pc.cap, pc.join)) {
            double q = real_grid_at((i / pc.nx) * pc.px + i % pc.nx);
            v[0] += g_at(i) * t_at(i);
            v[1] += q * t_at(i);
            v[2] += q;
            v[3] += t_at(i);
            v[4] += 1.0lf;
        }
    reduce_workgroup(v);
}
