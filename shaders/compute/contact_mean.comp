// p *= p_factor, u *= u_factor (load control's rescaling, as scale.comp does it; none when both are 1),
// then the mean of u + g0 over the elastic patches: slots (sum, count).
#version 450
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 256) in;
#define SLOTS 2u
#define MAX_SLOTS 0u
#define PARTIALS_BINDING 3
#include "chunks.glsl"
#include "patch_sets.glsl"
#include "reduce.glsl"
FIELD(0, p)
FIELD(1, u)
FIELD_IN(2, g0)
layout(push_constant) uniform Push { double cap; double p_factor; double u_factor; uint n; } pc;

void main()
{
    double v[SLOTS] = double[SLOTS](0.0lf, 0.0lf);
    bool rescale = pc.p_factor != 1.0lf || pc.u_factor != 1.0lf;
    for (uint i = gl_GlobalInvocationID.x; i < pc.n; i += grid_stride()) {
        double pi = p_at(i), ui = u_at(i);
        if (rescale) {
            pi *= pc.p_factor;
            ui *= pc.u_factor;
            p_put(i, pi);
            u_put(i, ui);
        }
        if (elastic(pi, pc.cap)) {
            v[0] += ui + g0_at(i);
            v[1] += 1.0lf;
        }
    }
    reduce_workgroup(v);
}
