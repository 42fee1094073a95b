// g = u + g0 - w and its statistics: slots (sum of g^2 over the elastic patches, their count,
// sum of g^2 over the moving ones, the largest bound violation, sum of g^2 over p = 0, g < 0); with
// the flag (a preconditioned plan) also the preconditioner's input for a step without a join, z = g
// on the moving patches and 0 elsewhere (precondition_mask.comp's, fused).
#version 450
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 256) in;
#define SLOTS 5u
#define MAX_SLOTS 8u
#define PARTIALS_BINDING 5
#include "chunks.glsl"
#include "patch_sets.glsl"
#include "reduce.glsl"
FIELD_IN(0, p)
FIELD_IN(1, u)
FIELD_IN(2, g0)
FIELD_OUT(3, g)
FIELD_OUT(4, z)
layout(push_constant) uniform Push { double w; double cap; uint n; uint mask; } pc;

void main()
{
    double v[SLOTS] = double[SLOTS](0.0lf, 0.0lf, 0.0lf, 0.0lf, 0.0lf);
    for (uint i = gl_GlobalInvocationID.x; i < pc.n; i += grid_stride()) {
        double pi = p_at(i), gi = u_at(i) + g0_at(i) - pc.w;
        g_put(i, gi);
        if (pc.mask != 0u)
            z_put(i, in_preconditioned_step(pi, gi, 0u) ? gi : 0.0lf);
        if (elastic(pi, pc.cap)) {
            v[0] += gi * gi;
            v[1] += 1.0lf;
        } else {
            v[3] = max(v[3], pi > 0.0lf ? gi : -gi);
            if (pi == 0.0lf && gi < 0.0lf)
                v[4] += gi * gi;
        }
        if (moving(pi, gi, pc.cap))
            v[2] += gi * gi;
    }
    reduce_workgroup(v);
}
