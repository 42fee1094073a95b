import os
import subprocess

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
