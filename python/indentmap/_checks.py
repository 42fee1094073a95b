"""Arguments checked for their kind before they reach the library, which checks their ranges and names the
parameter in its message. A conversion such as ``int(2.5)`` or ``bool("no")`` would pass a value the caller
never meant without a word, and ``float("x")`` would fail without naming the parameter."""
import numbers
import operator
import os

import numpy as np

SEED_LIMIT = 2 ** 64  # the library's seeds are unsigned 64-bit integers


def real(name, value):
    """value as a float: a real number (an int, a float or a numpy scalar), not a bool or a string."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError(f"{name}: expected a real number, got {value!r}")
    return float(value)


def integer(name, value):
    """value as an int: an integer, a numpy integer or a 0-d integer array (not a bool, and not a float even
    when whole)."""
    if isinstance(value, (bool, np.bool_)) or (isinstance(value, np.ndarray) and value.dtype == bool):
        raise TypeError(f"{name}: expected an integer, got {value!r}")
    try:
        return operator.index(value)
    except TypeError:
        raise TypeError(f"{name}: expected an integer, got {value!r}") from None


def c_int(name, value):
    """An integer that C's int holds (one beyond would be Python's OverflowError, naming nothing)."""
    value = integer(name, value)
    if not -(2 ** 31) <= value < 2 ** 31:
        raise ValueError(f"{name} = {value}: expected an integer in [-2^31, 2^31 - 1]")
    return value


def flag(name, value):
    """value as a bool: True or False (numpy's too), not a truthy string or number."""
    if not isinstance(value, (bool, np.bool_)):
        raise TypeError(f"{name}: expected True or False, got {value!r}")
    return bool(value)


def seed(value):
    """A seed as the library takes it: an integer in [0, 2^64 - 1] (one outside would wrap to another)."""
    value = integer("seed", value)
    if not 0 <= value < SEED_LIMIT:
        raise ValueError(f"seed = {value}: expected an integer in [0, 2^64 - 1]")
    return value


def path(name, value):
    """value as a path (str or bytes, as os.fspath gives it): a str, bytes or os.PathLike."""
    try:
        return os.fspath(value)
    except TypeError:
        raise TypeError(f"{name}: expected a path (str, bytes or os.PathLike), got {value!r}") from None


def text(name, value):
    """value, a str."""
    if not isinstance(value, str):
        raise TypeError(f"{name}: expected a string, got {value!r}")
    return value
