// modes[k] *= spectrum[k]: a real (even) kernel's spectrum times complex modes (re, im pairs).
#version 450
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 256) in;
#include "chunks.glsl"
#include "patch_sets.glsl"
FIELD(0, modes)
FIELD_IN(1, spectrum)
layout(push_constant) uniform Push { uint count; } pc;

void main()
{
    for (uint k = gl_GlobalInvocationID.x; k < pc.count; k += grid_stride()) {
        modes_put(2u * k, modes_at(2u * k) * spectrum_at(k));
        modes_put(2u * k + 1u, modes_at(2u * k + 1u) * spectrum_at(k));
    }
}
