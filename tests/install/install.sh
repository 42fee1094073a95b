#!/usr/bin/env bash
# Installs the build into a scratch prefix, then builds and runs tests/install/consumer.c against
# it twice, with pkg-config and with find_package(indentmap), and pip-installs the Python package
# over it. Fails when a header, the library, the .pc file, the CMake package or the Python build is
# missing or wrong.
# Where the library was built with MPI, tests/install/consumer_mpi.c (indentmap/mpi.h, which includes
# <mpi.h>) is built the same ways, with pkg-config's indentmap-mpi and find_package's indentmap::mpi and
# indentmap::indentmap_static, and run on 2 ranks by MPIEXEC (P8: no MPI include path before).
#   install.sh BUILD_DIR SOURCE_DIR [MPIEXEC]
set -euo pipefail
build=$1 source=$2 mpiexec=${3:-}
prefix=$(mktemp -d)
trap 'rm -rf "$prefix"' EXIT
cmake --install "$build" --prefix "$prefix" >/dev/null
lib=$(find "$prefix" -name 'libindentmap.so' -printf '%h\n' | head -1)
[ -n "$lib" ] || { echo "install: no libindentmap.so under $prefix" >&2; exit 1; }
soname=$(objdump -p "$lib/libindentmap.so" | awk '/SONAME/ {print $2}')
case "$soname" in libindentmap.so.[0-9]*) ;; *) echo "install: SONAME '$soname'" >&2; exit 1 ;; esac
[ -f "$lib/libindentmap.a" ] || { echo "install: no static library" >&2; exit 1; }
# HDF5 files are read by a program of the build that the library starts (src/formats/hdf5_child.c).
[ -x "$prefix/libexec/indentmap-hdf5-read" ] || { echo "install: no libexec/indentmap-hdf5-read" >&2; exit 1; }

export PKG_CONFIG_PATH="$lib/pkgconfig"
# shellcheck disable=SC2046
cc -std=c11 -Wall -Wextra -Werror -o "$prefix/consumer_pc" "$source/consumer.c" \
   $(pkg-config --cflags --libs indentmap) -lm -Wl,-rpath,"$lib"
"$prefix/consumer_pc"
# The headers are C++-clean (extern "C"): the same program compiled and linked as C++.
# shellcheck disable=SC2046
c++ -std=c++17 -Wall -Wextra -Werror -x c++ -o "$prefix/consumer_cxx" "$source/consumer.c" -x none \
    $(pkg-config --cflags --libs indentmap) -Wl,-rpath,"$lib"
"$prefix/consumer_cxx"
# The static library with `pkg-config --static`: every member of the archive linked (whole-archive),
# so that a dependency missing from the .pc file's Requires.private or Libs.private fails here whatever
# the consumer happens to call (libyaml, FFTW-MPI and MPI were missing: a program calling
# im_scene_run did not link).
# shellcheck disable=SC2046
cc -std=c11 -o "$prefix/consumer_static" "$source/consumer.c" \
   $(pkg-config --cflags indentmap) -Wl,--whole-archive "$lib/libindentmap.a" -Wl,--no-whole-archive \
   $(pkg-config --static --libs indentmap | sed 's/-lindentmap//') -lm
"$prefix/consumer_static"

cmake -S "$source" -B "$prefix/consumer_build" -DCMAKE_PREFIX_PATH="$prefix" \
      -DCMAKE_BUILD_RPATH="$lib" >/dev/null
cmake --build "$prefix/consumer_build" >/dev/null
"$prefix/consumer_build/consumer"
# The program must have been linked with the shared library, not with a copy of it.
# (ldd's output is read whole first: `grep -q` would stop reading early, and under pipefail the
# SIGPIPE that ldd then gets fails the pipeline now and then.)
libraries=$(ldd "$prefix/consumer_build/consumer")
grep -q "$soname" <<<"$libraries" || { echo "install: the consumer is not linked with $soname" >&2; exit 1; }
# indentmap::indentmap_static: the archive, not the shared library.
"$prefix/consumer_build/consumer_static"
libraries=$(ldd "$prefix/consumer_build/consumer_static")
! grep -q "$soname" <<<"$libraries" || { echo "install: consumer_static is linked with $soname" >&2; exit 1; }

if grep -q "define IM_HAVE_MPI 1" "$prefix/include/indentmap/mpi_config.h"; then
  [ -n "$mpiexec" ] || { echo "install: a library built with MPI, and no MPIEXEC to run its consumer" >&2; exit 1; }
  source "$source/../mpi/open_mpi_env.sh"
  # shellcheck disable=SC2046
  cc -std=c11 -Wall -Wextra -Werror -o "$prefix/consumer_mpi_pc" "$source/consumer_mpi.c" \
     $(pkg-config --cflags --libs indentmap-mpi) -lm -Wl,-rpath,"$lib"
  # shellcheck disable=SC2046
  cc -std=c11 -o "$prefix/consumer_mpi_static_pc" "$source/consumer_mpi.c" $(pkg-config --cflags indentmap-mpi) \
     -Wl,--whole-archive "$lib/libindentmap.a" -Wl,--no-whole-archive \
     $(pkg-config --static --libs indentmap-mpi | sed 's/-lindentmap//') -lm
  # A C++-only project: its FindMPI finds no MPI for C, so the package's targets must carry the build's MPI.
  cmake -S "$source/cxx" -B "$prefix/consumer_cxx_build" -DCMAKE_PREFIX_PATH="$prefix" \
        -DCMAKE_BUILD_RPATH="$lib" >/dev/null
  cmake --build "$prefix/consumer_cxx_build" >/dev/null
  for program in consumer_mpi_pc consumer_mpi_static_pc consumer_build/consumer_mpi consumer_build/consumer_mpi_static \
                 consumer_cxx_build/consumer_mpi_cxx; do
    OMP_NUM_THREADS=1 "$mpiexec" -n 2 -x OMP_NUM_THREADS "$prefix/$program"
  done
  libraries=$(ldd "$prefix/consumer_build/consumer_mpi")
  grep -q "$soname" <<<"$libraries" || { echo "install: consumer_mpi is not linked with $soname" >&2; exit 1; }
elif [ -e "$lib/pkgconfig/indentmap-mpi.pc" ]; then
  echo "install: indentmap-mpi.pc installed by a build without MPI" >&2
  exit 1
fi

# The Python package, pip-installed on top of the installed library (from a copy of python/, so the
# build leaves nothing in the source tree), must import and solve.
cp -r "$source/../../python" "$prefix/python_source"
PKG_CONFIG_PATH="$lib/pkgconfig" /usr/bin/python3 -m pip install --quiet --no-build-isolation --no-deps \
  --no-index --target "$prefix/site" "$prefix/python_source" 2>&1 | grep -v "Running pip as the 'root' user" || true
PYTHONPATH="$prefix/site" /usr/bin/python3 -c '
import sys, indentmap as im
assert im._core.__file__.startswith(sys.argv[1]), im._core.__file__
history = im.indent(im.generate(32, slope=0.05, lambda_s=2), approaches=[1.0])
assert history["contact_patches"][0] > 0
print("install: pip-installed Python package", im.__version__, "solved", history["contact_patches"][0], "patches")
' "$prefix/site"
echo "install: pkg-config, find_package (shared and static) and pip consumers ran against $soname${mpiexec:+, MPI ones on 2 ranks}"
