// The second half of an ordered reduction (reduce.glsl): one workgroup folds the partials of
// `groups` workgroups, slot by slot, in a fixed order, into result[0 .. slots).
#version 450
layout(local_size_x = 256) in;

layout(std430, set = 0, binding = 0) readonly buffer Partials { double partials[]; };
layout(std430, set = 0, binding = 1) writeonly buffer Result { double result[]; };
layout(push_constant) uniform Push { uint groups; uint slots; uint max_slots; } pc;

shared double folded[256];

double fold(uint slot, double a, double b)
{
    return ((pc.max_slots >> slot) & 1u) != 0u ? max(a, b) : a + b;
}

void main()
{
    uint t = gl_LocalInvocationID.x;
    for (uint k = 0u; k < pc.slots; ++k) {
        double v = t < pc.groups ? partials[t * pc.slots + k] : 0.0lf;
        for (uint g = t + 256u; g < pc.groups; g += 256u)
            v = fold(k, v, partials[g * pc.slots + k]);
        folded[t] = v;
        barrier();
        for (uint half_width = 128u; half_width > 0u; half_width >>= 1) {
            if (t < half_width)
                folded[t] = fold(k, folded[t], folded[t + half_width]);
            barrier();
        }
        if (t == 0u)
            result[k] = folded[0];
        barrier();
    }
}
