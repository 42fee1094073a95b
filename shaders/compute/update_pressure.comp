// u -= tau K t; p -= tau t on the step's set, projected onto [0, cap]; joining by the gap, the
// penetrating patches at p = 0 join with min(-tau g, cap): slots (patches that differ from the
// plain step, 1 if any joined, then summary.comp's three of the new p: sum of p, patches with
// p > 0, largest p, summed in its order). The changes themselves are appended to the change list
// (point_loads.glsl) while it has room; the host zeroes its count before the pass.
#version 450
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 256) in;
#define SLOTS 5u
#define MAX_SLOTS 18u
#define PARTIALS_BINDING 5
#include "chunks.glsl"
#include "patch_sets.glsl"
#include "reduce.glsl"
#include "point_loads.glsl"
FIELD(0, p)
FIELD(1, u)
FIELD_IN(2, g)
FIELD_IN(3, t)
FIELD_IN(4, real_grid)
layout(std430, set = 0, binding = 6) buffer ChangeCount { uint change_count; };
layout(std430, set = 0, binding = 7) writeonly buffer ChangeIndex { uint change_index[]; };
layout(std430, set = 0, binding = 8) writeonly buffer ChangeValue { double change_value[]; };
layout(push_constant) uniform Push { double tau; double cap; uint nx; uint ny; uint px; uint join; } pc;

void main()
{
    double v[SLOTS] = double[SLOTS](0.0lf, 0.0lf, 0.0lf, 0.0lf, 0.0lf);
    uint n = pc.nx * pc.ny;
    for (uint i = gl_GlobalInvocationID.x; i < n; i += grid_stride()) {
        double c = 0.0lf, pi = p_at(i), gi = g_at(i), after = pi;
        u_put(i, u_at(i) - pc.tau * real_grid_at((i / pc.nx) * pc.px + i % pc.nx));
        if (in_step(pi, gi, pc.cap, pc.join)) {
            double next = pi - pc.tau * t_at(i);
            if (pi == 0.0lf && next > 0.0lf)
                v[1] = 1.0lf;
            after = project(next, pc.cap);
            p_put(i, after);
            c = after - next;
        } else if (pc.join == JOIN_BY_GAP && pi == 0.0lf && gi < 0.0lf) {
            after = project(-pc.tau * gi, pc.cap);
            p_put(i, after);
            c = after;
            v[1] = 1.0lf;
        }
        if (after > 0.0lf) {
            v[2] += after;
            v[3] += 1.0lf;
            v[4] = max(v[4], after);
        }
        if (c != 0.0lf) {
            v[0] += 1.0lf;
            uint slot = atomicAdd(change_count, 1u);
            if (slot < CHANGE_CAPACITY) {
                change_index[slot] = i;
                change_value[slot] = c;
            }
        }
    }
    reduce_workgroup(v);
}
