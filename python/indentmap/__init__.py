"""indentmap: rough-surface indentation from Python, over libindentmap.

Surfaces, the FFT boundary-element solver, the paper's theory and the off-screen renderer, with numpy
arrays in and out. Arrays are (ny, nx) float64 with ``a[y, x]`` the value at patch (x, y), lengths in
units of the grid spacing ``delta`` unless you give physical ones, stresses in units of E*.

Errors are ``indentmap.Error`` subclasses; ``str(error)`` is the library's message, ``error.status`` its code:
InvalidArgument and FormatError (also ValueError), FileError (OSError), OutOfMemory (MemoryError),
NumericError (ArithmeticError), NotConverged, EdgeContact, Unsupported, Interrupted.
"""
from . import _wait_policy  # first: libgomp reads its wait policy when _core loads it
from . import _core
from ._core import (EdgeContact, Error, FileError, FormatError, Interrupted, InvalidArgument, NotConverged,
                    NumericError, OutOfMemory, Unsupported)
from . import theory
from .render import Figure, Image, View3DFigure, animate, contact_map, height_map, renderer, use_backend, view3d
from .scene import check_scene, run_scene, run_scene_from_record
from .solver import (Cone, Flat, Indentation, Plan, Sphere, adhesion, indent, indent_run, read_history, unloading,
                     write_analysis)
from .surface import (Generated, Topography, generate, generate_recorded, histogram, prepare, psd, read,
                      read_generator, statistics, write)

__version__ = _core.library_version


def memory_limit(limit=None):
    """The cap, in bytes, on the memory the library lets a run use (0: none, the machine's memory).

    With ``limit`` (bytes; 0 removes the cap) sets it first, for the whole process, like the ``indentmap``
    program's ``IM_MEMORY_LIMIT_MIB``: work that would need more than the cap (or than the machine has)
    is refused up front with ``OutOfMemory`` naming what and how much, instead of starting to swap.

    Example: ``im.memory_limit(8 << 30)`` caps the library at 8 GiB; ``im.memory_limit()`` reads it.
    """
    return _core.memory_limit() if limit is None else _core.memory_limit(int(limit))


def info(backend="auto"):
    """The text ``indentmap info`` prints, byte for byte: the version, the libraries in use (FFTW, GSL,
    libpng), the OpenMP thread count, the OpenGL renderer of ``backend`` ('auto', 'egl' or 'osmesa'; the
    program's IM_RENDER_BACKEND is its own) and the Vulkan devices the GPU engine could use.

    A machine without OpenGL says 'render backend: unavailable (...)'; a renderer that opens a context
    and then fails raises ``Unsupported`` (where the program exits 1), a backend of another name
    ``InvalidArgument``.

    Example: ``print(im.info(), end="")``."""
    return _core.info_text(backend)


def solver_memory(n, m=None, periodic=False, device="cpu"):
    """The memory an n x m solve's plan needs (m defaults to n), before any plan is made, on the engine
    ``device`` takes ('cpu', 'gpu' or 'auto'): a dict of ``gpu`` (whether the GPU engine solves it),
    ``host_bytes`` (the plan's host memory at its peak), ``device_bytes`` (on the GPU: its buffers, as
    the engine counts them), ``device_memory`` (the GPU's), ``device`` (its name, or 'cpu') and ``note``
    ('auto' on the CPU because the GPU is too small: why). The surface and fields are not counted. The
    program's ``indentmap info --memory N``; ``OutOfMemory`` naming the device when 'gpu' would not hold it.

    Example: ``im.solver_memory(32768, periodic=True, device="gpu")["device_bytes"] / 2**30``."""
    return _core.solver_memory(int(n), int(n if m is None else m), bool(periodic), device)


def formats():
    """The text ``indentmap formats`` prints, byte for byte: the surface formats ``read`` reads, its own
    readers, then each of Gwyddion's file modules where the build has them (found as ``read`` finds
    indentmap-gwyddion-read: set INDENTMAP_GWYDDION_READER to choose it). ``FileError`` where that
    program cannot be run or lists nothing.

    Example: ``".x3p" in im.formats()``."""
    return _core.formats_text()


__all__ = ["Cone", "EdgeContact", "Error", "FileError", "Figure", "Flat", "FormatError", "Generated", "Image", "Indentation",
           "Interrupted", "InvalidArgument", "NotConverged", "NumericError", "OutOfMemory", "Plan", "Sphere", "Topography", "View3DFigure",
           "Unsupported", "adhesion", "animate", "check_scene", "contact_map", "formats", "generate", "generate_recorded", "height_map", "histogram", "indent", "indent_run", "info", "memory_limit", "prepare", "psd", "read", "read_generator", "read_history", "renderer",
           "run_scene", "run_scene_from_record", "solver_memory", "statistics", "theory", "unloading", "use_backend", "view3d", "write", "write_analysis"]
