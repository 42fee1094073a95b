// The local (Winkler) guess p = max(w - g0, 0) / k0, stored when store != 0: slot (sum of p).
#version 450
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 256) in;
#define SLOTS 1u
#define MAX_SLOTS 0u
#define PARTIALS_BINDING 2
#include "chunks.glsl"
#include "patch_sets.glsl"
#include "reduce.glsl"
FIELD_IN(0, g0)
FIELD(1, p)
layout(push_constant) uniform Push { double w; double k0; uint n; uint store; } pc;

void main()
{
    double v[SLOTS] = double[SLOTS](0.0lf);
    for (uint i = gl_GlobalInvocationID.x; i < pc.n; i += grid_stride()) {
        double pi = g0_at(i) < pc.w ? (pc.w - g0_at(i)) / pc.k0 : 0.0lf;
        if (pc.store != 0u)
            p_put(i, pi);
        v[0] += pi;
    }
    reduce_workgroup(v);
}
