// The patch sets of the Polonsky-Keer iteration (src/solver/engine.h): elastic = 0 < p < cap;
// moving = elastic, or at the cap and unloading (g > 0). Without a hardness the cap is +inf (the
// host passes IEEE infinity in the push constants).
bool elastic(double p, double cap) { return p > 0.0lf && p < cap; }
bool moving(double p, double g, double cap) { return elastic(p, cap) || (p == cap && g > 0.0lf); }
// How the penetrating patches at p = 0 join in a step (engine.h, enum solver_join): not at all, by
// the gap (plain PK), or in the step's direction (the step's set holds them).
const uint JOIN_BY_GAP = 1u;
const uint JOIN_IN_DIRECTION = 2u;
bool in_step(double p, double g, double cap, uint join)
{
    return moving(p, g, cap) || (join == JOIN_IN_DIRECTION && p == 0.0lf && g < 0.0lf);
}
// The same without a cap (a preconditioner excludes one).
bool in_preconditioned_step(double p, double g, uint join)
{
    return p > 0.0lf || (join == JOIN_IN_DIRECTION && p == 0.0lf && g < 0.0lf);
}
double project(double p, double cap) { return p < 0.0lf ? 0.0lf : (p > cap ? cap : p); }

uint grid_stride() { return gl_NumWorkGroups.x * gl_WorkGroupSize.x; }
