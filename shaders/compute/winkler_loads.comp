// The local guess's load at several approaches in one pass (pk.c's bisection of the approach under load
// control): slot k, the sum of max(w_k - g0, 0) / k0 as winkler.comp sums it for w_k (p not stored).
#version 450
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 256) in;
#define SLOTS 7u
#define MAX_SLOTS 0u
#define PARTIALS_BINDING 1
#include "chunks.glsl"
#include "patch_sets.glsl"
#include "reduce.glsl"
FIELD_IN(0, g0)
layout(push_constant) uniform Push { double w[SLOTS]; double k0; uint n; } pc;

void main()
{
    double v[SLOTS] = double[SLOTS](0.0lf, 0.0lf, 0.0lf, 0.0lf, 0.0lf, 0.0lf, 0.0lf);
    for (uint i = gl_GlobalInvocationID.x; i < pc.n; i += grid_stride())
        for (uint k = 0u; k < SLOTS; ++k)
            v[k] += g0_at(i) < pc.w[k] ? (pc.w[k] - g0_at(i)) / pc.k0 : 0.0lf;
    reduce_workgroup(v);
}
