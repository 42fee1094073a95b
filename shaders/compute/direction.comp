// The search direction t = source + beta t on the step's set, 0 elsewhere, written also into
// the px x py transform grid with its zero padding (one pass instead of two).
#version 450
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 256) in;
#include "patch_sets.glsl"
layout(std430, set = 0, binding = 0) readonly buffer Pressure { double p[]; };
layout(std430, set = 0, binding = 1) readonly buffer Gap { double g[]; };
layout(std430, set = 0, binding = 2) readonly buffer Source { double src[]; };
layout(std430, set = 0, binding = 3) buffer Direction { double t[]; };
layout(std430, set = 0, binding = 4) writeonly buffer Real { double real_grid[]; };
layout(push_constant) uniform Push { double beta; double cap; uint nx; uint ny; uint px; uint py; uint join; } pc;

void main()
{
    uint count = pc.px * pc.py;
    for (uint k = gl_GlobalInvocationID.x; k < count; k += grid_stride()) {
        uint x = k % pc.px, y = k / pc.px;
        double value = 0.0lf;
        if (x < pc.nx && y < pc.ny) {
            uint i = y * pc.nx + x;
            value = in_step(p[i], g[i], pc.cap, pc.join) ? src[i] + pc.beta * t[i] : 0.0lf;
            t[i] = value;
        }
        real_grid[k] = value;
    }
}
