"""indentmap: rough-surface indentation from Python, over libindentmap.

Surfaces, the FFT boundary-element solver, the paper's theory and the off-screen renderer, with numpy
arrays in and out. Arrays are (ny, nx) float64 with ``a[y, x]`` the value at patch (x, y), lengths in
units of the grid spacing ``delta`` unless you give physical ones, stresses in units of E*.

Errors are ``indentmap.Error`` subclasses; ``str(error)`` is the library's message, ``error.status`` its code:
InvalidArgument and FormatError (also ValueError), FileError (OSError), OutOfMemory (MemoryError),
NumericError (ArithmeticError), NotConverged, EdgeContact, Unsupported, Interrupted.
"""
from . import _core
from ._core import (EdgeContact, Error, FileError, FormatError, Interrupted, InvalidArgument, NotConverged,
                    NumericError, OutOfMemory, Unsupported)
from . import theory
from .render import Figure, Image, contact_map, height_map, renderer
from .scene import run_scene
from .solver import Cone, Flat, Indentation, Plan, Sphere, indent
from .surface import Topography, generate, histogram, prepare, psd, read, statistics, write

__version__ = _core.library_version

__all__ = ["Cone", "EdgeContact", "Error", "FileError", "Figure", "Flat", "FormatError", "Image", "Indentation",
           "Interrupted", "InvalidArgument", "NotConverged", "NumericError", "OutOfMemory", "Plan", "Sphere", "Topography",
           "Unsupported", "contact_map", "generate", "height_map", "histogram", "indent", "prepare", "psd", "read", "renderer",
           "run_scene", "statistics", "theory", "write"]
