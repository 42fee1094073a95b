// The workgroup half of the GPU engine's ordered reductions (included after SLOTS and MAX_SLOTS are
// defined). Each of a reduction's fixed number of workgroups folds its 256 threads' values in a
// fixed tree and writes one partial per slot; reduce_finish.comp folds the partials in a fixed order.
// So a reduction's result depends on the grid size only, never on timing. Slot k is a maximum when
// bit k of MAX_SLOTS is set, a sum otherwise; counts are summed as doubles (exact below 2^53).
layout(std430, set = 0, binding = PARTIALS_BINDING) buffer Partials { double partials[]; };

shared double folded[SLOTS][256];

double fold(uint slot, double a, double b)
{
    return ((MAX_SLOTS >> slot) & 1u) != 0u ? max(a, b) : a + b;
}

void reduce_workgroup(double value[SLOTS])
{
    uint t = gl_LocalInvocationID.x;
    for (uint k = 0u; k < SLOTS; ++k)
        folded[k][t] = value[k];
    barrier();
    for (uint half_width = 128u; half_width > 0u; half_width >>= 1) {
        if (t < half_width)
            for (uint k = 0u; k < SLOTS; ++k)
                folded[k][t] = fold(k, folded[k][t], folded[k][t + half_width]);
        barrier();
    }
    if (t == 0u)
        for (uint k = 0u; k < SLOTS; ++k)
            partials[gl_WorkGroupID.x * SLOTS + k] = folded[k][0];
}
