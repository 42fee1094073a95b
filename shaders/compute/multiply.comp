// modes[k] *= spectrum[k]: a real (even) kernel's spectrum times complex modes (re, im pairs); with
// invert, times its inverse scale / spectrum[k] (0 where it is 0), the periodic preconditioner (K's
// inverse, E* |q| / 2 / (nx ny) from 2 / (E* |q|) / (nx ny), scale 1 / (nx ny)^2) without a table.
#version 450
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 256) in;
#include "chunks.glsl"
#include "patch_sets.glsl"
FIELD(0, modes)
FIELD_IN(1, spectrum)
layout(push_constant) uniform Push { double scale; uint count; uint invert; } pc;

void main()
{
    for (uint k = gl_GlobalInvocationID.x; k < pc.count; k += grid_stride()) {
        const double s = spectrum_at(k);
        const double factor = pc.invert == 0u ? s : (s > 0.0lf ? pc.scale / s : 0.0lf);
        modes_put(2u * k, modes_at(2u * k) * factor);
        modes_put(2u * k + 1u, modes_at(2u * k + 1u) * factor);
    }
}
