"""Builds indentmap._core against an installed libindentmap, found with pkg-config (set PKG_CONFIG_PATH
for a prefix of your own):  pip install --no-build-isolation ./python"""
import glob
import os
import subprocess

import numpy
from setuptools import Extension, setup


def pkg_config(*flags):
    try:
        return subprocess.check_output(["pkg-config", *flags, "indentmap"], text=True).split()
    except (OSError, subprocess.CalledProcessError) as error:
        raise SystemExit("indentmap: libindentmap was not found by pkg-config; install it first "
                         "(cmake --install build) and set PKG_CONFIG_PATH to its lib/pkgconfig") from error


here = os.path.dirname(os.path.abspath(__file__))
library_dirs = [flag[2:] for flag in pkg_config("--libs-only-L")]
core = Extension("indentmap._core", sources=sorted(glob.glob(os.path.join("src", "*.c"))),
                 include_dirs=[numpy.get_include()] + [flag[2:] for flag in pkg_config("--cflags-only-I")],
                 library_dirs=library_dirs, runtime_library_dirs=library_dirs, libraries=["indentmap"],
                 extra_compile_args=["-std=c11"])
setup(version=pkg_config("--modversion")[0], ext_modules=[core])
