"""Every option of Indentation(...) and generate(...) given a wrong kind or an out-of-range value: refused at
once with TypeError or ValueError naming the parameter and what was expected (issue 32: some were accepted
without a word, truncated, wrapped or converted, or failed only at the first step)."""
import inspect
import math

import numpy as np
import pytest

import indentmap as im

HEIGHTS = np.zeros((16, 16))
NAN, INF = math.nan, math.inf

# (option, value, exception, what the message says)
INDENTATION = [
    ("heights", np.zeros(5), TypeError, r"heights: expected a 2-D array"),
    ("heights", "flat", TypeError, r"heights: expected a 2-D array"),
    ("punch", "cone", TypeError, r"punch: expected Cone, Sphere, Flat or a profile array"),
    ("punch", im.Cone(-5), ValueError, r"alpha = -5: expected 0 < alpha < 90"),
    ("punch", im.Cone("80"), TypeError, r"Cone.alpha: expected a real number, got '80'"),
    ("punch", im.Sphere(NAN), ValueError, r"sphere radius = nan: expected a finite radius > 0"),
    ("punch", im.Flat(True), TypeError, r"Flat.radius: expected a real number, got True"),
    ("control", "force", ValueError, r"control 'force': expected 'displacement', 'load' or 'mean_gap'"),
    ("control", 1, TypeError, r"control: expected a string, got 1"),
    ("largest", -1, ValueError, r"largest approach = -1: expected a finite value >= 0"),
    ("largest", INF, ValueError, r"largest approach = inf: expected a finite value >= 0"),
    ("largest", "1", TypeError, r"largest: expected a real number, got '1'"),
    ("delta", 0, ValueError, r"delta = 0: expected > 0"),
    ("delta", NAN, ValueError, r"delta = nan: expected > 0"),
    ("delta", None, TypeError, r"delta: expected a real number, got None"),
    ("e_star", -1, ValueError, r"E\* = -1: expected a finite modulus > 0"),
    ("e_star", INF, ValueError, r"E\* = inf: expected a finite modulus > 0"),
    ("tol", -1e-6, ValueError, r"tol = -1e-06: expected 1e-15 <= tol <= 0.5"),
    ("tol", NAN, ValueError, r"tol = nan: expected 1e-15 <= tol <= 0.5"),
    ("tol", 1e-17, ValueError, r"tol = 1e-17: expected 1e-15 <= tol <= 0.5"),
    ("tol", "x", TypeError, r"tol: expected a real number, got 'x'"),
    ("max_iterations", 0, ValueError, r"max_iterations = 0: expected >= 1"),
    ("max_iterations", 2.5, TypeError, r"max_iterations: expected an integer, got 2.5"),
    ("crop", "no", TypeError, r"crop: expected True or False, got 'no'"),
    ("window_margin", -1, ValueError, r"window_margin = -1: expected >= 0"),
    ("window_margin", 1.5, TypeError, r"window_margin: expected an integer, got 1.5"),
    ("axis", (1000, 5), ValueError, r"axis = \(1000, 5\): the punch's axis lies outside the 16 x 16 surface"),
    ("axis", (NAN, 5), ValueError, r"axis = \(nan, 5\): the punch's axis lies outside"),
    ("axis", 5, TypeError, r"axis: expected \(x, y\), two numbers, got 5"),
    ("axis", ("8", 8), TypeError, r"axis x: expected a real number, got '8'"),
    ("device", "tpu", ValueError, r"device 'tpu': expected 'cpu', 'gpu' or 'auto'"),
    ("device", 0, TypeError, r"device: expected a string, got 0"),
    ("hardness", -1, ValueError, r"hardness = -1: expected a finite pressure cap H_p > 0"),
    ("hardness", NAN, ValueError, r"hardness = nan: expected a finite pressure cap"),
    ("periodic", "yes", TypeError, r"periodic: expected True or False, got 'yes'"),
    ("slope_definition", "x", ValueError, r"slope_definition 'x': expected 'spectral' or 'fd'"),
    ("adhesion_work", -1, ValueError, r"adhesion work = -1: expected a finite work of adhesion w >= 0"),
    ("adhesion_range", INF, ValueError, r"adhesion range = inf: expected a finite gap delta_c > 0"),
    ("adhesion_law", "lennard-jones", ValueError, r"adhesion_law 'lennard-jones': expected 'maugis-dugdale' or 'exponential'"),
    ("adhesion_law", 3, TypeError, r"adhesion_law: expected a string, got 3"),
    ("adhesion_zone", -1, ValueError, r"adhesion zone = -1: expected a finite number of patches P > 0"),
    ("adhesion_zone", 1, ValueError, r"adhesion zone = 1 patches without adhesion: expected a work and a range"),
    ("quality", "best", ValueError, r"quality = 'best': expected draft, standard or publication"),
    ("quality", 3, TypeError, r"quality: expected a string, got 3"),
    ("length_unit", "furlong", ValueError, r"length_unit 'furlong': expected a length unit"),
    ("length_unit", 1, TypeError, r"length_unit: expected a string, got 1"),
    ("e_star_unit", None, TypeError, r"e_star_unit: expected a string, got None"),
    ("plain_pk", "yes", TypeError, r"plain_pk: expected True or False, got 'yes'"),
    ("measure", 1, TypeError, r"measure: expected True or False, got 1"),
    ("wisdom", 5, TypeError, r"wisdom: expected a path \(str, bytes or os.PathLike\), got 5"),
    ("wisdom", "/proc/no such folder/wisdom", im.FileError, r"wisdom /proc/no such folder/wisdom"),
    ("colour", "red", TypeError, r"unexpected keyword argument 'colour'"),
]

GENERATE = [
    ("n", 0, ValueError, r"grid 0 x 0: expected each side in \[2, 65536\]"),
    ("n", 2.5, TypeError, r"n: expected an integer, got 2.5"),
    ("n", "8", TypeError, r"n: expected an integer, got '8'"),
    ("m", -3, ValueError, r"grid 32 x -3: expected each side"),
    ("m", 32.0, TypeError, r"m: expected an integer, got 32.0"),
    ("delta", 0, ValueError, r"delta = 0: expected a finite value > 0"),
    ("delta", INF, ValueError, r"delta = inf: expected a finite value > 0"),
    ("hurst", 1, ValueError, r"hurst = 1: expected 0 < H < 1"),
    ("hurst", NAN, ValueError, r"hurst = nan: expected 0 < H < 1"),
    ("hurst", "0.8", TypeError, r"hurst: expected a real number, got '0.8'"),
    ("lambda_s", 1, ValueError, r"lambda_s = 1: expected a finite value >= 2"),
    ("lambda_r", 2, ValueError, r"lambda_r = 2: expected a finite value > lambda_s = 4"),
    ("lambda_r", NAN, ValueError, r"lambda_r = nan: expected a finite value > lambda_s"),
    ("lambda_0", -1, ValueError, r"lambda_0 = -1: expected >= lambda_r = 32"),
    ("lambda_0", 5, ValueError, r"lambda_0 = 5: expected >= lambda_r = 32"),
    ("lambda_0", NAN, ValueError, r"lambda_0 = nan: expected >= lambda_r = 32"),
    ("slope", -0.1, ValueError, r"slope \(h'rms\) = -0.1: expected a finite value >= 0"),
    ("slope", INF, ValueError, r"slope \(h'rms\) = inf: expected a finite value >= 0"),
    ("height_rms", NAN, ValueError, r"height-rms = nan: expected a finite value >= 0"),
    ("height_rms", "1", TypeError, r"height_rms: expected a real number, got '1'"),
    ("slope_definition", "fft", ValueError, r"slope_definition 'fft': expected 'spectral' or 'fd'"),
    ("seed", -1, ValueError, r"seed = -1: expected an integer in \[0, 2\^64 - 1\]"),
    ("seed", 2 ** 64, ValueError, r"seed = 18446744073709551616: expected an integer in \[0, 2\^64 - 1\]"),
    ("seed", True, TypeError, r"seed: expected an integer, got True"),
    ("seed", 1.5, TypeError, r"seed: expected an integer, got 1.5"),
    ("sigma", 1, TypeError, r"unexpected keyword argument 'sigma'"),
]


def indentation(**options):
    arguments = dict(heights=HEIGHTS, largest=1.0) | options
    return im.Indentation(arguments.pop("heights"), **arguments)


@pytest.mark.parametrize("option, value, error, message", INDENTATION)
def test_indentation_refuses(option, value, error, message):
    with pytest.raises(error, match=message):
        indentation(**{option: value})


@pytest.mark.parametrize("option, value, error, message", GENERATE)
def test_generate_refuses(option, value, error, message):
    with pytest.raises(error, match=message):
        im.generate(**{"n": 32, option: value})


@pytest.mark.parametrize("function, table", [(im.Indentation.__init__, INDENTATION), (im.generate, GENERATE)])
def test_every_option_is_in_the_table(function, table):
    options = set(inspect.signature(function).parameters) - {"self"}
    assert options <= {row[0] for row in table}


def test_the_edges_of_the_ranges_are_accepted():
    """What the rows above refuse is refused for being wrong, not for being given: the limits themselves pass."""
    assert indentation(axis=(0, 16), max_iterations=1, window_margin=0, crop=np.bool_(False)).window[2] == 16
    assert im.generate(32, seed=2 ** 64 - 1, lambda_0=32, m=np.int64(16)).shape == (16, 32)
    assert not np.array_equal(im.generate(32, seed=2 ** 64 - 1), im.generate(32, seed=0))
