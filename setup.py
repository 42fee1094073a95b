"""`pip install --no-build-isolation .`: CMake builds the static library, the extension module over it and
the programs the library starts to read files (indentmap-hdf5-read; indentmap-gwyddion-read where Gwyddion is
installed) in build-pip/ (kept: a second install rebuilds only what changed); they go into the package beside the
extension module, where the library looks for them. No library is installed.
CMAKE_ARGS passes options to CMake ("-DIM_GPU=OFF")."""
import os
import re
import shlex
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

here = os.path.dirname(os.path.abspath(__file__))


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = os.path.abspath(self.build_temp)
        subprocess.check_call(["cmake", "-S", here, "-B", build, "-DBUILD_TESTING=OFF",
                               f"-DPython3_EXECUTABLE={sys.executable}", *shlex.split(os.environ.get("CMAKE_ARGS", ""))])
        subprocess.check_call(["cmake", "--build", build, "--parallel", str(os.cpu_count() or 1),
                               "--target", "indentmap_python", "indentmap_python_programs"])
        built = os.path.join(build, "python", "indentmap")
        package = os.path.dirname(self.get_ext_fullpath(ext.name))
        os.makedirs(package, exist_ok=True)
        for name in os.listdir(built):  # the extension module and the reading programs; the .py come from python/
            if not name.endswith(".py"):
                shutil.copy2(os.path.join(built, name), package)


with open(os.path.join(here, "CMakeLists.txt")) as cmake:
    version = re.search(r"project\(indentmap VERSION ([0-9.]+)", cmake.read()).group(1)
setup(version=version, ext_modules=[Extension("indentmap._core", sources=[])], cmdclass={"build_ext": CMakeBuild},
      options={"build": {"build_base": "build-pip"}})
