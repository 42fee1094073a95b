// real = src on the nx x ny quadrant of the px x py transform grid, 0 elsewhere (the zero padding of
// the half-space's linear convolution; px = nx, py = ny for the periodic one).
#version 450
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 256) in;
#include "patch_sets.glsl"
layout(std430, set = 0, binding = 0) readonly buffer Source { double src[]; };
layout(std430, set = 0, binding = 1) writeonly buffer Real { double real_grid[]; };
layout(push_constant) uniform Push { uint nx; uint ny; uint px; uint py; } pc;

void main()
{
    uint count = pc.px * pc.py;
    for (uint i = gl_GlobalInvocationID.x; i < count; i += grid_stride()) {
        uint x = i % pc.px, y = i / pc.px;
        real_grid[i] = x < pc.nx && y < pc.ny ? src[y * pc.nx + x] : 0.0lf;
    }
}
