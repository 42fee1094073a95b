"""Call overhead of a solve from Python: the wall time of Indentation.step() against the library's own
time for the same step (im_step_result.seconds, what the CLI reports in history.csv), median of
repeats, on grids from 32^2 to 512^2. Usage (after a build):

    PYTHONPATH=build/python OMP_NUM_THREADS=1 /usr/bin/python3 bench/bench_python.py [REPEATS]
"""
import os
import platform
import statistics
import sys
import time

import indentmap as im


def measure(n, repeats):
    heights = im.generate(n, slope=0.08, seed=1)
    walls, inside = [], []
    for _ in range(repeats):
        run = im.Indentation(heights, largest=n / 16.0, tol=1e-8)
        start = time.perf_counter()
        result = run.step(n / 16.0)
        walls.append(time.perf_counter() - start)
        inside.append(result["seconds"])
    wall, lib = statistics.median(walls), statistics.median(inside)
    return wall, lib, result["iterations"]


def main():
    repeats = int(sys.argv[1]) if len(sys.argv) > 1 else 9
    print(f"# {platform.processor() or platform.machine()}, {os.cpu_count()} cores, "
          f"OMP_NUM_THREADS={os.environ.get('OMP_NUM_THREADS', 'unset')}, median of {repeats}")
    print("grid, iterations, python step (s), library step (s), overhead (s), overhead / library")
    for n in (32, 64, 128, 256, 512):
        wall, lib, iterations = measure(n, repeats)
        print(f"{n}^2, {iterations}, {wall:.6f}, {lib:.6f}, {wall - lib:.2e}, {(wall - lib) / lib:.2e}")


if __name__ == "__main__":
    main()
