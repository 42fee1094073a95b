// The search direction t = source + beta t on the step's set, 0 elsewhere, written also into
// the px x py transform grid with its zero padding (one pass instead of two).
#version 450
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 256) in;
#include "chunks.glsl"
#include "patch_sets.glsl"
FIELD_IN(0, p)
FIELD_IN(1, g)
FIELD_IN(2, src)
FIELD(3, t)
FIELD_OUT(4, real_grid)
layout(push_constant) uniform Push { double beta; double cap; uint nx; uint ny; uint px; uint py; uint join; } pc;

void main()
{
    uint count = pc.px * pc.py;
    for (uint k = gl_GlobalInvocationID.x; k < count; k += grid_stride()) {
        uint x = k % pc.px, y = k / pc.px;
        double value = 0.0lf;
        if (x < pc.nx && y < pc.ny) {
            uint i = y * pc.nx + x;
            value = in_step(p_at(i), g_at(i), pc.cap, pc.join) ? src_at(i) + pc.beta * t_at(i) : 0.0lf;
            t_put(i, value);
        }
        real_grid_put(k, value);
    }
}
