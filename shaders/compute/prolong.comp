// The cascade's prolongation on the device (src/solver/cascade.c, prolong_pressure): each patch takes
// the coarse level's pressure of its 2 x 2 block, 0 where its gap is infinite (a flat punch cannot
// touch there). The coarse answer lies at the start of the coarse field (cx wide): the levels share
// their buffers, so it is read from p and written to another field (a patch's coarse value may lie
// where another patch is written).
#version 450
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 256) in;
#include "chunks.glsl"
#include "patch_sets.glsl"
FIELD_IN(0, gap0)
FIELD_IN(1, coarse)
FIELD_OUT(2, fine)
layout(push_constant) uniform Push { uint nx; uint ny; uint cx; } pc;

void main()
{
    uint count = pc.nx * pc.ny;
    for (uint i = gl_GlobalInvocationID.x; i < count; i += grid_stride()) {
        double g = gap0_at(i);
        bool finite = !isinf(g) && !isnan(g);
        fine_put(i, finite ? coarse_at((i / pc.nx / 2u) * pc.cx + (i % pc.nx) / 2u) : 0.0lf);
    }
}
