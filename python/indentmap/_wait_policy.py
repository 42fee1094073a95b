"""The OpenMP wait policy of the library's threads in Python: the ``indentmap`` program's (src/cli/wait_policy.c).

libgomp reads its wait policy once, when it is loaded, and by default spins 300000 times at every barrier
before it sleeps. On shared cores a spinning thread holds the core that the thread it waits for needs: through
the library, two threads were 3-10x slower than one beside one busy process (issue 33). The program re-executes
itself with a short spin; a Python process cannot, but it loads libgomp only with the extension, so importing
indentmap sets the same spin count first, unless the user chose (OMP_WAIT_POLICY or GOMP_SPINCOUNT set) or
another module loaded libgomp already, when the setting could no longer take effect.
"""
import os

# CLI_SPIN_COUNT of src/cli/cli.h (python/tests/test_wait_policy.py checks that they agree)
SPIN_COUNT = "3000"


def _libgomp_loaded():
    try:
        with open("/proc/self/maps", encoding="utf-8", errors="replace") as maps:
            return any("libgomp" in line for line in maps)
    except OSError:
        return False


def prefer_short_spinning():
    """Sets GOMP_SPINCOUNT for libgomp's load, unless the user chose a policy or libgomp is loaded already."""
    if "OMP_WAIT_POLICY" in os.environ or "GOMP_SPINCOUNT" in os.environ or _libgomp_loaded():
        return
    os.environ["GOMP_SPINCOUNT"] = SPIN_COUNT


prefer_short_spinning()
