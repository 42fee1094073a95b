// dst = the nx x ny quadrant of the px x py transform grid (the convolution's result).
#version 450
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 256) in;
#include "patch_sets.glsl"
layout(std430, set = 0, binding = 0) readonly buffer Real { double real_grid[]; };
layout(std430, set = 0, binding = 1) writeonly buffer Destination { double dst[]; };
layout(push_constant) uniform Push { uint nx; uint ny; uint px; } pc;

void main()
{
    uint count = pc.nx * pc.ny;
    for (uint i = gl_GlobalInvocationID.x; i < count; i += grid_stride())
        dst[i] = real_grid[(i / pc.nx) * pc.px + i % pc.nx];
}
