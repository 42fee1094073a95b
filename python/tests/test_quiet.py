"""A quiet library under Python: scenes report progress and log lines to callables (nothing on stderr),
and Ctrl-C stops a long solve or a scene promptly with KeyboardInterrupt, leaving the plan usable."""
import contextlib
import json
import os
import re
import signal
import subprocess
import sys
import tempfile
import threading
import time

import numpy as np
import pytest

import indentmap as im
from conftest import run_cli

SCENE = """[scene]
name = quiet
output = {output}
[surfaces]
n = 64
hurst = 0.8
lambda_s = 4
slopes = 0, 0.08
seeds = 1:3
[punch]
shape = cone
alpha = 80
[loading]
load_star = 600
control = load
steps = 100:600:3
[output]
table = yes
plots = fig5
"""


def write_scene(folder, output):
    path = folder / "quiet.ini"
    path.write_text(SCENE.format(output=output))
    return path


@contextlib.contextmanager
def captured_fd2():
    """What is written on file descriptor 2 (by C or Python) while the block runs: a list, filled after it."""
    written = []
    with tempfile.TemporaryFile() as sink:
        saved = os.dup(2)
        os.dup2(sink.fileno(), 2)
        try:
            yield written
        finally:
            os.dup2(saved, 2)
            os.close(saved)
            sink.seek(0)
            written.append(sink.read())


def test_scene_progress_and_log_lines_are_the_clis(cli, tmp_path):
    """The stages, counts and lines the CLI prints on stderr reach the callables instead, the same."""
    events, lines = [], []
    scene = write_scene(tmp_path, tmp_path / "py")
    im.run_scene(scene, progress=lambda stage, done, total: events.append((stage, done, total)),
                 log=lambda level, message: lines.append((level, message)))
    write_scene(tmp_path, tmp_path / "cli")
    printed = run_cli(cli, "run", scene).stderr.splitlines()
    assert [message for _, message in lines] == [line.removeprefix("indentmap: ") for line in printed]
    assert all(level == 20 for level, _ in lines)  # logging.INFO: stage lines, no warnings
    for stage in ("table", "histories"):
        counted = [line for line in printed if re.match(rf"indentmap: {stage}: \d+ surfaces: ", line)]
        assert len(counted) == 1, printed
        total = int(re.match(rf"indentmap: {stage}: (\d+) surfaces", counted[0]).group(1))
        assert total == 4  # the smooth family once, the rough one per seed
        assert [e for e in events if e[0] == stage] == [(stage, k, total) for k in range(1, total + 1)]
    assert {e[0] for e in events} == {"table", "histories"}


def test_library_writes_nothing_on_stderr(tmp_path):
    """Scene stage lines, a stale lock's notice, solves and the theory: nothing reaches fd 2; the notice
    goes to the log callable as a warning."""
    output = tmp_path / "out"
    output.mkdir()
    ended = subprocess.Popen(["true"])
    ended.wait()
    dead = ended.pid
    (output / ".lock").write_text(f"{dead}\n")
    lines = []
    with captured_fd2() as written:
        im.run_scene(write_scene(tmp_path, output), quiet=False, log=lambda level, message: lines.append((level, message)))
        im.run_scene(write_scene(tmp_path, output), resume=True)  # the default: the "indentmap" logger
        im.Plan(32).solve(np.full((32, 32), 0.5) - np.eye(32) * 0.5, 0.2)
        im.theory.area_ratio([0.01, 0.08], alpha=80)
    assert written == [b""]
    assert (30, f"taking over the stale lock {output}/.lock of pid {dead}, which no longer runs") in lines
    assert any(level == 20 and message.startswith("table: 4 surfaces") for level, message in lines)


def test_a_callback_that_raises_stops_the_scene(tmp_path):
    def progress(stage, done, total):
        raise ValueError(f"stop at {stage} {done}")
    with pytest.raises(ValueError, match="stop at table 1"):
        im.run_scene(write_scene(tmp_path, tmp_path / "out"), progress=progress)


def interrupt_after(seconds):
    """Sends this process SIGINT from a timer thread after `seconds`; returns the list its time goes into."""
    sent = []

    def send():
        sent.append(time.perf_counter())
        os.kill(os.getpid(), signal.SIGINT)
    threading.Timer(seconds, send).start()
    return sent


def interrupt_when(folder, pattern, timeout=60.0):
    """Sends this process SIGINT from a thread as soon as a file matching `pattern` is in `folder` (a
    fixed delay is not enough: a fast machine finishes a small scene first); returns the list its time
    goes into."""
    sent = []

    def watch():
        deadline = time.perf_counter() + timeout
        while not any(folder.glob(pattern)) and time.perf_counter() < deadline:
            time.sleep(0.002)
        sent.append(time.perf_counter())
        os.kill(os.getpid(), signal.SIGINT)
    threading.Thread(target=watch, daemon=True).start()
    return sent


def rough_cone_gap(n):
    y, x = np.mgrid[0:n, 0:n]
    gap = np.hypot(x - (n - 1) / 2, y - (n - 1) / 2) / np.tan(np.radians(80)) - im.generate(n, slope=0.08, seed=1)
    return gap - gap.min()


def test_ctrl_c_stops_a_long_solve_and_the_plan_stays_usable():
    n = 512  # a solve of about a second on one core, some 60 iterations of ~15 ms with the cascade's
    gap = rough_cone_gap(n)
    plan = im.Plan(n, tol=1e-12)
    sent = interrupt_after(0.2)
    with pytest.raises(KeyboardInterrupt):
        plan.solve(gap, 20.0)
    latency = time.perf_counter() - sent[0]
    start = time.perf_counter()
    pressure, _, result = plan.solve(gap, 20.0)
    whole = time.perf_counter() - start
    assert latency < min(0.5, whole / 4), (latency, whole)
    fresh_pressure, _, fresh = im.Plan(n, tol=1e-12).solve(gap, 20.0)
    assert result["iterations"] == fresh["iterations"]
    assert pressure.tobytes() == fresh_pressure.tobytes()


def test_ctrl_c_stops_a_scene_and_resume_finishes_it(tmp_path):
    """No Python callable runs during the scene (quiet, no progress), so only the stop flag can end it early."""
    scene = SCENE.replace("seeds = 1:3", "seeds = 1:30")  # 31 surfaces, some seconds in all
    path = tmp_path / "long.ini"
    path.write_text(scene.format(output=tmp_path / "out"))
    sent = interrupt_when(tmp_path / "out" / "table", "member_*.csv")  # once the first surface is kept
    with pytest.raises(KeyboardInterrupt):
        im.run_scene(path, quiet=True)
    latency = time.perf_counter() - sent[0]
    assert latency < 0.5, latency  # the next check comes between two solver steps of a 64^2 surface
    lines = []
    im.run_scene(path, resume=True, log=lambda level, message: lines.append(message))
    counts = [re.match(r"(?:table|histories): 31 surfaces: (\d+) solved, (\d+) read back", line) for line in lines]
    solved, read_back = (sum(int(m.group(k)) for m in counts if m) for k in (1, 2))
    assert solved > 0 and read_back > 0, lines  # stopped before the end, keeping what it had finished


def test_ctrl_c_in_a_solve_made_by_a_callback(tmp_path):
    """A log callable (called on the main thread) that solves: SIGINT stops that inner solve, whose
    KeyboardInterrupt stops the scene; Python's own handler is back afterwards."""
    gap = rough_cone_gap(512)
    plan = im.Plan(512, tol=1e-12)
    sent = []

    def log(level, message):
        if not sent:
            sent.extend(interrupt_after(0.2))
            plan.solve(gap, 20.0)
    with pytest.raises(KeyboardInterrupt):
        im.run_scene(write_scene(tmp_path, tmp_path / "out"), log=log)
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
    interrupt_after(0.05)
    with pytest.raises(KeyboardInterrupt):
        time.sleep(5)  # the plain handler, not one left armed by the calls


def test_quiet_silences_the_log_but_not_progress(tmp_path):
    """quiet drops the stage lines only: a progress bar (or a callable that cancels by raising) still runs."""
    events, lines = [], []
    im.run_scene(write_scene(tmp_path, tmp_path / "out"), quiet=True,
                 progress=lambda stage, done, total: events.append((stage, done, total)),
                 log=lambda level, message: lines.append(message))
    assert lines == []
    for stage in ("table", "histories"):
        assert [e for e in events if e[0] == stage] == [(stage, k, 4) for k in range(1, 5)]


REENTRANT = """
import json
import sys
import indentmap as im

def loads():
    history = im.indent(im.generate(32, slope=0.05, lambda_s=2, seed=6), approaches=[0.5, 1.0])
    return history["load"].tolist()

outer, inner, alone = sys.argv[1:4]
seen = []

def progress(stage, done, total):
    if not seen:  # the first call comes from a solver thread, inside the outer run's callback lock
        seen.extend((im.run_scene(inner, quiet=True), loads()))

im.run_scene(outer, progress=progress, log=lambda level, message: None)
print(json.dumps(seen + [im.run_scene(alone, quiet=True), loads()]))
"""


def test_a_progress_callback_may_run_another_scene(tmp_path):
    """A callback that runs a scene and solves inside another scene's run: both finish (it waited forever on
    the library's lock, issue 32), the inner scene's table is the one a run of its own writes; the inner solve
    gives the loads a solve of its own gives."""
    folders = {name: tmp_path / name for name in ("outer", "inner", "alone")}
    scenes = []
    for name, folder in folders.items():
        path = tmp_path / f"{name}.ini"
        path.write_text(SCENE.format(output=folder).replace("name = quiet", f"name = {name}"))
        scenes.append(path)
    done = subprocess.run([sys.executable, "-c", REENTRANT, *map(str, scenes)], timeout=120, capture_output=True,
                          text=True, env=dict(os.environ, OMP_WAIT_POLICY="passive"))
    assert done.returncode == 0, done.stderr
    inner, solved, alone, solved_alone = json.loads(done.stdout)
    assert (inner, alone) == (str(folders["inner"]), str(folders["alone"]))
    # equal to the solver's tolerance: a solve nested in the run's OpenMP team runs on other threads
    assert solved == pytest.approx(solved_alone, rel=im._core.default_tol)
    table = (folders["inner"] / "table1.csv").read_bytes()
    assert table and table == (folders["alone"] / "table1.csv").read_bytes()
    assert (folders["outer"] / "table1.csv").is_file()
