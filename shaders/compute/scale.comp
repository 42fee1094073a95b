// data[i] *= factor for i < count: the smallest pipeline (one buffer, push constants), used by the
// GPU engine and by tests/test_gpu_fft.c to check the Vulkan layer.
#version 450
#extension GL_ARB_gpu_shader_fp64 : enable
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 256) in;
#include "chunks.glsl"

FIELD(0, data)

// std430 push constants: the double first (offset 0, 8-byte aligned), then the uint (offset 8);
// the host's struct { double factor; uint32_t count; } has the same layout (16 bytes with padding).
layout(push_constant) uniform Push {
    double factor;
    uint count;
} pc;

void main()
{
    uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
    for (uint i = gl_GlobalInvocationID.x; i < pc.count; i += stride)
        data_put(i, data_at(i) * pc.factor);
}
