// The changes that clipping and joining make in a Polonsky-Keer step (update_pressure.comp appends
// them; point_loads.comp adds K of them to u). At most CHANGE_CAPACITY are kept: the host adds them
// by direct summation only when the step's count is at most its plan's direct limit, which never
// exceeds this (engine_gpu.c), and recomputes u by FFT otherwise.
#define CHANGE_CAPACITY 256u
