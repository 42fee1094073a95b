import os
import subprocess
import threading
import time

import numpy as np
import pytest

import indentmap as im


@pytest.fixture(scope="session")
def cli():
    """The indentmap program of the same build (set by ctest), for comparisons."""
    path = os.environ.get("IM_CLI")
    if not path:
        pytest.skip("IM_CLI is not set (run through ctest)")
    return path


def run_cli(cli, *args, cwd=None):
    env = dict(os.environ, OMP_WAIT_POLICY="passive")
    return subprocess.run([cli, *map(str, args)], cwd=cwd, env=env, check=True, capture_output=True, text=True)


@pytest.fixture(scope="session")
def rough64():
    return im.generate(64, slope=0.1, seed=2)


def longest_pause_of_this_thread(work):
    """Runs work() in a thread while this one counts; the longest this thread went without running during
    work(), and how long work() took. What work() raised is raised here."""
    span = {}

    def timed():
        span["start"] = time.perf_counter()
        try:
            work()
        except Exception as error:
            span["error"] = error
        span["end"] = time.perf_counter()

    thread = threading.Thread(target=timed)
    ticks = []
    thread.start()
    while thread.is_alive():
        ticks.append(time.perf_counter())
    thread.join()
    if "error" in span:
        raise span["error"]
    inside = [t for t in ticks if span["start"] <= t <= span["end"]]
    edges = [span["start"]] + inside + [span["end"]]
    return max(b - a for a, b in zip(edges, edges[1:])), span["end"] - span["start"]


def gil_held_share(make_work, attempts=3):
    """The longest pause of this thread as a share of the call, and the pause and the call's seconds, at the
    least of up to `attempts` calls of make_work()'s work (set up outside the timing; stops at a share under
    a half). A call that holds the GIL pauses this thread for all of it at every attempt; a machine under load
    can also deschedule this thread for a while, but not at every attempt (CI: 0.191 s of a 0.372 s call once
    at load 12)."""
    least = None
    for _ in range(attempts):
        pause, duration = longest_pause_of_this_thread(make_work())
        if least is None or pause / duration < least[0]:
            least = (pause / duration, pause, duration)
        if least[0] < 0.5:
            break
    return least
