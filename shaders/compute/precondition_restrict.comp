// The sums of z = M g over the step's set: slots (sum of z there, count, <g, z> there: what
// precondition_centre.comp returns for a mean of 0, summed in its order). z is left as it is
// elsewhere: no pass reads it there (engine.h).
#version 450
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 256) in;
#define SLOTS 3u
#define MAX_SLOTS 0u
#define PARTIALS_BINDING 3
#include "chunks.glsl"
#include "patch_sets.glsl"
#include "reduce.glsl"
FIELD_IN(0, p)
FIELD_IN(1, g)
FIELD_IN(2, z)
layout(push_constant) uniform Push { uint n; uint join; } pc;

void main()
{
    double v[SLOTS] = double[SLOTS](0.0lf, 0.0lf, 0.0lf);
    for (uint i = gl_GlobalInvocationID.x; i < pc.n; i += grid_stride())
        if (in_preconditioned_step(p_at(i), g_at(i), pc.join)) {
            v[0] += z_at(i);
            v[1] += 1.0lf;
            v[2] += g_at(i) * z_at(i);
        }
    reduce_workgroup(v);
}
