// modes[k] *= spectrum[k]: a real (even) kernel's spectrum times complex modes (re, im pairs).
#version 450
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 256) in;
#include "patch_sets.glsl"
layout(std430, set = 0, binding = 0) buffer Modes { double modes[]; };
layout(std430, set = 0, binding = 1) readonly buffer Spectrum { double spectrum[]; };
layout(push_constant) uniform Push { uint count; } pc;

void main()
{
    for (uint k = gl_GlobalInvocationID.x; k < pc.count; k += grid_stride()) {
        modes[2u * k] *= spectrum[k];
        modes[2u * k + 1u] *= spectrum[k];
    }
}
