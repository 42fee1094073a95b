// g = u + g0 - w and its statistics: slots (sum of g^2 over the elastic patches, their count,
// sum of g^2 over the moving ones, the largest bound violation, sum of g^2 over p = 0, g < 0).
#version 450
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 256) in;
#define SLOTS 5u
#define MAX_SLOTS 8u
#define PARTIALS_BINDING 4
#include "patch_sets.glsl"
#include "reduce.glsl"
layout(std430, set = 0, binding = 0) readonly buffer Pressure { double p[]; };
layout(std430, set = 0, binding = 1) readonly buffer Displacement { double u[]; };
layout(std430, set = 0, binding = 2) readonly buffer Gap0 { double g0[]; };
layout(std430, set = 0, binding = 3) writeonly buffer Gap { double g[]; };
layout(push_constant) uniform Push { double w; double cap; uint n; } pc;

void main()
{
    double v[SLOTS] = double[SLOTS](0.0lf, 0.0lf, 0.0lf, 0.0lf, 0.0lf);
    for (uint i = gl_GlobalInvocationID.x; i < pc.n; i += grid_stride()) {
        double pi = p[i], gi = u[i] + g0[i] - pc.w;
        g[i] = gi;
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
