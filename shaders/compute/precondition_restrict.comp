// M g restricted to p > 0 (0 elsewhere): slots (sum of z there, count).
#version 450
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 256) in;
#define SLOTS 2u
#define MAX_SLOTS 0u
#define PARTIALS_BINDING 2
#include "chunks.glsl"
#include "patch_sets.glsl"
#include "reduce.glsl"
FIELD_IN(0, p)
FIELD(1, z)
layout(push_constant) uniform Push { uint n; } pc;

void main()
{
    double v[SLOTS] = double[SLOTS](0.0lf, 0.0lf);
    for (uint i = gl_GlobalInvocationID.x; i < pc.n; i += grid_stride()) {
        if (p_at(i) > 0.0lf) {
            v[0] += z_at(i);
            v[1] += 1.0lf;
        } else
            z_put(i, 0.0lf);
    }
    reduce_workgroup(v);
}
