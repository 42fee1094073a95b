// dst = the nx x ny quadrant of the px x py transform grid (the convolution's result).
#version 450
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 256) in;
#include "chunks.glsl"
#include "patch_sets.glsl"
FIELD_IN(0, real_grid)
FIELD_OUT(1, dst)
layout(push_constant) uniform Push { uint nx; uint ny; uint px; } pc;

void main()
{
    uint count = pc.nx * pc.ny;
    for (uint i = gl_GlobalInvocationID.x; i < count; i += grid_stride())
        dst_put(i, real_grid_at((i / pc.nx) * pc.px + i % pc.nx));
}
