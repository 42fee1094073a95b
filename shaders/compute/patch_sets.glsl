// The patch sets of the Polonsky-Keer iteration (src/solver/engine.h): elastic = 0 < p < cap;
// moving = elastic, or at the cap and unloading (g > 0). Without a hardness the cap is +inf (the
// host passes IEEE infinity in the push constants).
bool elastic(double p, double cap) { return p > 0.0lf && p < cap; }
bool moving(double p, double g, double cap) { return elastic(p, cap) || (p == cap && g > 0.0lf); }
double project(double p, double cap) { return p < 0.0lf ? 0.0lf : (p > cap ? cap : p); }

uint grid_stride() { return gl_NumWorkGroups.x * gl_WorkGroupSize.x; }
