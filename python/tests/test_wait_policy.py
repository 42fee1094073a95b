"""The wait policy a Python process's OpenMP threads get: the program's short spin unless the user chose one
(libgomp prints what it resolved, with OMP_DISPLAY_ENV, when it loads)."""
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

from indentmap import _wait_policy


def resolved_spin_count(**env):
    clean = {k: v for k, v in os.environ.items() if k not in ("OMP_WAIT_POLICY", "GOMP_SPINCOUNT")}
    clean.update(env, OMP_DISPLAY_ENV="verbose")
    run = subprocess.run([sys.executable, "-c", "import indentmap"], env=clean, capture_output=True, text=True,
                         check=True)
    counts = re.findall(r"GOMP_SPINCOUNT = '(\d+)'", run.stderr)
    assert counts, run.stderr
    return int(counts[-1])


def test_default_is_the_programs_short_spin():
    assert resolved_spin_count() == int(_wait_policy.SPIN_COUNT)


@pytest.mark.parametrize("env, expected", [({"OMP_WAIT_POLICY": "passive"}, 0), ({"GOMP_SPINCOUNT": "12345"}, 12345)])
def test_the_users_choice_is_kept(env, expected):
    assert resolved_spin_count(**env) == expected


def test_an_active_policy_is_kept():
    assert resolved_spin_count(OMP_WAIT_POLICY="active") > int(_wait_policy.SPIN_COUNT)


def test_same_count_as_the_program():
    source = Path(os.environ.get("IM_SOURCE_DIR", Path(__file__).resolve().parents[2]))
    header = (source / "src" / "cli" / "cli.h").read_text(encoding="utf-8")
    assert re.search(r'#define CLI_SPIN_COUNT "(\d+)"', header).group(1) == _wait_policy.SPIN_COUNT
