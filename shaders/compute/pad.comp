// real = src on the nx x ny quadrant of the px x py transform grid, 0 elsewhere (the zero padding of
// the half-space's linear convolution; px = nx, py = ny for the periodic one).
#version 450
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 256) in;
#include "chunks.glsl"
#include "patch_sets.glsl"
FIELD_IN(0, src)
FIELD_OUT(1, real_grid)
layout(push_constant) uniform Push { uint nx; uint ny; uint px; uint py; } pc;

void main()
{
    uint count = pc.px * pc.py;
    for (uint i = gl_GlobalInvocationID.x; i < count; i += grid_stride()) {
        uint x = i % pc.px, y = i / pc.px;
        real_grid_put(i, x < pc.nx && y < pc.ny ? src_at(y * pc.nx + x) : 0.0lf);
    }
}
