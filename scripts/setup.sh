#!/usr/bin/env bash
# Installs the Debian 12 packages indentmap needs (when missing) and builds it.
#   scripts/setup.sh [BUILD_DIR] [extra cmake arguments...]
# As root it runs apt-get; otherwise it prints the exact command to run and stops.
set -euo pipefail
cd "$(dirname "$0")/.."

PACKAGES=(
  build-essential cmake pkg-config         # compiler (gcc with OpenMP), build system
  libfftw3-dev                             # FFTs with the OpenMP threads library (libfftw3_omp)
  libgsl-dev                               # quadrature and special functions for the theory
  libpng-dev                               # PNG frames and figures
  libjansson-dev                           # JSON run records and sidecars
  libinih-dev                              # INI scene files
  libcmocka-dev                            # unit tests (one program per module, run by ctest)
  libegl-dev libgl-dev libosmesa6-dev      # headless OpenGL: EGL first, OSMesa fallback
  libegl-mesa0 libgl1-mesa-dri             # Mesa's EGL and llvmpipe software renderer
  libcairo2-dev libfreetype-dev            # annotations, text, PDF/SVG figures
  fonts-dejavu-core                        # the font figures are set in
  libgif-dev                               # animated GIFs
  python3-dev python3-numpy                # the Python package (python/): CPython and numpy C APIs
  python3-setuptools python3-wheel python3-pip python3-pytest python3-venv  # its pip build, its tests (a venv for pip install .)
  jupyter-nbconvert python3-ipykernel python3-matplotlib  # tests only: the notebooks (python/notebooks) executed, their plots
  python3-build                            # tests only: the wheel built by python3 -m build
  chromium                                 # tests only: the viewer page (index.html) in headless Chromium
  libnetcdf-dev                            # NetCDF surfaces (ContactMechanics/SurfaceTopography layout)
  libzip-dev libxml2-dev nettle-dev        # ISO 25178-72 .x3p surfaces: zip archive around XML, MD5 checksums
  libhdf5-dev libyaml-dev                  # plain HDF5 surfaces; contact.engineering containers' meta.yml
  hdf5-tools                               # tests only: h5dump, the independent reading of HDF5 heights
  openmpi-bin libopenmpi-dev libfftw3-mpi-dev  # one grid over MPI ranks (src/mpi/, optional: IM_MPI)
  libvulkan-dev libvkfft-dev glslang-dev glslang-tools spirv-tools  # the GPU solver engine (src/gpu/, optional: IM_GPU)
  mesa-vulkan-drivers vulkan-validationlayers  # lavapipe and the validation layers for its tests
  libgwyddion20-dev gwyddion               # instrument formats through Gwyddion's file modules (src/formats/gwyddion/, optional: IM_GWYDDION)
  clang-format-14                          # tests only: the C sources' style (.clang-format, ctest style)
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  cmd="apt-get update && DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends ${missing[*]}"
  if [ "$(id -u)" -eq 0 ]; then
    echo "setup: installing ${missing[*]}"
    bash -c "$cmd"
  else
    echo "setup: missing Debian packages; run as root:" >&2
    echo "  sudo bash -c '$cmd'" >&2
    exit 1
  fi
fi

build_dir=${1:-build}
shift || true
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build "$build_dir" -j "$(nproc)"
