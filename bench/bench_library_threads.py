"""A Python user's solves (issue 33, "threads that hold for library users"): bench_library_threads.c's two
solves through ``import indentmap``, not a test. A rough surface n x n (h'rms 0.08, seed 1), a cold 80 deg
cone solve to the approach whose smooth contact radius is n/5, then the periodic cell under a rigid flat at
mean pressure 0.004 E* (load 0.004 n^2), both at tol 1e-8. The thread count is OpenMP's (OMP_NUM_THREADS).
Prints the C program's CSV lines (the periodic line's result is its approach, as the C program's):

    PYTHONPATH=build/python /usr/bin/python3 bench/bench_library_threads.py [N]
"""
import math
import os
import sys
import time

import indentmap as im


def timed_step(run, target):
    wall, cpu = time.perf_counter(), time.process_time()
    result = run.step(target)
    return result, time.perf_counter() - wall, time.process_time() - cpu


def report(solve, n, result, wall, cpu, value):
    threads = os.environ.get("OMP_NUM_THREADS", os.cpu_count())
    print(f"{solve},{n},{threads},{wall:.4f},{cpu:.4f},{result['iterations']},{value!r},{result['contact_patches']}")


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 512
    heights = im.generate(n, slope=0.08, seed=1)
    approach = math.pi * n / (10 * math.tan(math.radians(80)))
    cone = im.Indentation(heights, im.Cone(80), largest=approach, tol=1e-8)
    result, wall, cpu = timed_step(cone, approach)
    report("cone", n, result, wall, cpu, result["load"])
    load = 0.004 * n * n
    periodic = im.Indentation(heights, None, control="load", largest=load, periodic=True, tol=1e-8)
    result, wall, cpu = timed_step(periodic, load)
    report("periodic", n, result, wall, cpu, result["approach"])


if __name__ == "__main__":
    main()
