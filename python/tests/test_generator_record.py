"""A surface generated and written from Python keeps its provenance (findings-recheck R5): with its generator's
record, write() leaves the sidecar `indentmap surface --out` writes, so that `indent` and scenes take the file's
h'rms as they take the program's file (spectral), and read_generator gives the record back."""
import json

import numpy as np
import pytest

import indentmap as im
from conftest import run_cli

# The program's options and generate_recorded's arguments for the same surfaces: the paper's slope target, and a
# height target measured by forward differences on a non-square grid with a roll-off plateau, and the default
# lambda_r of a grid taller than wide.
SURFACES = [
    (["--n", "64", "--slope", "0.1", "--seed", "11"], dict(n=64, slope=0.1, seed=11)),
    (["--n", "64", "--m", "48", "--hurst", "0.6", "--lambda-0", "128", "--height-rms", "2", "--slope-def", "fd",
      "--seed", "12"], dict(n=64, m=48, hurst=0.6, lambda_0=128.0, height_rms=2.0, slope_definition="fd", seed=12)),
    # taller than wide, lambda_r not given: the longer side, as the program's (Python took n, the width)
    (["--n", "32", "--m", "48", "--seed", "13"], dict(n=32, m=48, seed=13)),
    # seeds beyond JSON's signed 64-bit integers, written as the decimal typed (earlier: a negative integer)
    (["--n", "16", "--seed", "18446744073709551615"], dict(n=16, seed=2**64 - 1)),
    (["--n", "16", "--seed", "9223372036854775808"], dict(n=16, seed=2**63)),
]


def write_both(cli, tmp_path, options, arguments):
    """The program's file program/s.npy and Python's python/s.npy of the same surface; Python's Generated."""
    for folder in ("program", "python"):
        (tmp_path / folder).mkdir()
    run_cli(cli, "surface", *options, "--out", tmp_path / "program" / "s.npy")
    surface = im.generate_recorded(**arguments)
    im.write(tmp_path / "python" / "s.npy", surface.heights, surface.delta, generator=surface.generator)
    return surface


@pytest.mark.parametrize("options, arguments", SURFACES)
def test_python_writes_the_programs_sidecar(cli, tmp_path, options, arguments):
    surface = write_both(cli, tmp_path, options, arguments)
    np.testing.assert_array_equal(surface.heights, im.generate(**arguments))
    np.testing.assert_array_equal(surface.heights, im.read(tmp_path / "program" / "s.npy").heights)
    assert (tmp_path / "python" / "s.npy.json").read_bytes() == (tmp_path / "program" / "s.npy.json").read_bytes()
    assert im.read_generator(tmp_path / "program" / "s.npy") == surface.generator
    assert im.read_generator(tmp_path / "python" / "s.npy") == surface.generator
    assert f'"seed": {arguments["seed"]}' in (tmp_path / "program" / "s.npy.json").read_text()
    assert im.read_generator(tmp_path / "python" / "s.npy")["seed"] == arguments["seed"]


def test_an_earlier_builds_negative_seed_is_read_as_its_twos_complement(tmp_path):
    """A sidecar of an earlier build states a seed of 2**64 - 1 as -1: read_generator gives 2**64 - 1, which
    write records as that decimal; a seed below -2**63 or above 2**64 - 1 is refused naming it."""
    surface = im.generate_recorded(16, seed=2**64 - 1)
    earlier = dict(surface.generator, seed=-1)
    (tmp_path / "old.npy.json").write_text(json.dumps({"generator": earlier}))
    assert im.read_generator(tmp_path / "old.npy") == surface.generator
    im.write(tmp_path / "s.npy", surface.heights, generator=earlier)
    assert '"seed": 18446744073709551615' in (tmp_path / "s.npy.json").read_text()
    refused = r'generator: "seed": expected an integer in \[0, 18446744073709551615\]'
    for seed in (2**64, -2**63 - 1, 1.5, "1"):
        with pytest.raises(im.InvalidArgument, match=refused):
            im.write(tmp_path / "t.npy", surface.heights, generator=dict(surface.generator, seed=seed))


def test_a_record_read_back_writes_the_same_sidecar_beside_another_format(cli, tmp_path):
    """read_generator's record of the program's file, written with the generated heights as .gsf: the program's
    sidecar beside it (the program writes one for every --out, its statistics those of the heights generated,
    not of the .gsf's float32 copy)."""
    run_cli(cli, "surface", "--n", "32", "--seed", "5", "--out", tmp_path / "program.gsf")
    record = im.read_generator(tmp_path / "program.gsf")
    im.write(tmp_path / "python.gsf", im.generate(32, seed=5), generator=record)
    assert (tmp_path / "python.gsf.json").read_bytes() == (tmp_path / "program.gsf.json").read_bytes()


def history_without_timings(path):
    """history.csv's columns but the wall-clock seconds, which differ between two runs."""
    history = im.read_history(path)
    return {name: history[name] for name in history.dtype.names if name != "seconds"}


def assert_same_histories(a, b):
    assert a.keys() == b.keys()
    for name in a:
        np.testing.assert_array_equal(a[name], b[name], err_msg=name)


SCENE = """[scene]
name = provenance
[surfaces]
file = s.npy
[loading]
load_star = 200
[output]
table = yes
"""


def test_indent_and_scenes_give_the_programs_numbers_for_the_python_file(cli, tmp_path):
    """Table 1 and indent's eq. (12) columns of Python's file are the program's file's to the bit; the same
    heights written without the record are read as measured (forward differences): other numbers."""
    surface = write_both(cli, tmp_path, *SURFACES[0])
    (tmp_path / "bare").mkdir()
    im.write(tmp_path / "bare" / "s.npy", surface.heights, surface.delta)
    results = {}
    for folder in ("program", "python", "bare"):
        (tmp_path / folder / "s.ini").write_text(SCENE)
        run_cli(cli, "run", "s.ini", "--quiet", "--no-wisdom", "--out", "scene", cwd=tmp_path / folder)
        run_cli(cli, "indent", "s.npy", "--approach", "1,2", "--no-wisdom", "--out", "indent", cwd=tmp_path / folder)
        results[folder] = ((tmp_path / folder / "scene" / "table1.csv").read_text(),
                           history_without_timings(tmp_path / folder / "indent" / "history.csv"))
    assert results["python"][0] == results["program"][0]
    assert_same_histories(results["python"][1], results["program"][1])
    assert results["bare"][0] != results["program"][0]
    assert not np.array_equal(results["bare"][1]["area_ratio_gamma"], results["program"][1]["area_ratio_gamma"])
    # An array has no sidecar: Python's solver takes the program's numbers when told the h'rms definition.
    told = im.indent(surface.heights, approaches=[1, 2], slope_definition="spectral")
    np.testing.assert_array_equal(told["area_ratio_gamma"], results["program"][1]["area_ratio_gamma"])


def spoilt(record, change):
    record = dict(record)
    change(record)
    return record


@pytest.mark.parametrize("change, message", [
    (lambda r: r.pop("seed"), 'generator: "seed" is missing'),
    (lambda r: r.update(sead=3), 'generator: "sead": not a key of the record'),
    (lambda r: r.update(nx="64"), 'generator: "nx": expected an integer in \\[2, '),
    (lambda r: r.update(hurst="0.8"), 'generator: "hurst": expected a number'),
    (lambda r: r.update(target="slope"), 'generator: "target": expected "slope_rms" or "height_rms"'),
    (lambda r: r.update(slope_definition="fd"),
     'generator: "slope_definition": expected "spectral" or "finite-difference"'),
    (lambda r: r.update(hurst=1.5), "generator: hurst = 1.5: expected 0 < H < 1"),
    (lambda r: r.update(nx=32), "generator: nx = 32, ny = 64: expected the heights' shape, 64 x 64"),
    (lambda r: r.update(delta=0.5), "generator: delta = 0.5: expected delta = 1, the spacing written"),
])
def test_a_malformed_generator_is_refused_naming_the_key(tmp_path, change, message):
    surface = im.generate_recorded(64, seed=3)
    with pytest.raises(im.InvalidArgument, match=message):
        im.write(tmp_path / "s.npy", surface.heights, surface.delta, generator=spoilt(surface.generator, change))
    assert not (tmp_path / "s.npy").exists() and not (tmp_path / "s.npy.json").exists()


def test_a_generator_that_is_no_record_is_refused(tmp_path):
    surface = im.generate_recorded(16, seed=3)
    with pytest.raises(TypeError, match="generator: expected a dict, the generator's record"):
        im.write(tmp_path / "s.npy", surface.heights, generator=json.dumps(surface.generator))
    with pytest.raises(ValueError, match="generator: expected a record of numbers and strings"):
        im.write(tmp_path / "s.npy", surface.heights, generator=dict(surface.generator, slope_rms=float("nan")))
    heights = surface.heights.copy()
    heights[2, 1] = np.nan
    with pytest.raises(im.NumericError, match="heights written with a generator"):
        im.write(tmp_path / "s.npy", heights, generator=surface.generator)


def test_read_generator_of_files_without_a_record(tmp_path):
    heights = im.generate(16, seed=3)
    im.write(tmp_path / "bare.npy", heights)
    im.write(tmp_path / "bare.gsf", heights)
    assert im.read_generator(tmp_path / "bare.npy") is None  # a sidecar of units only
    assert im.read_generator(tmp_path / "bare.gsf") is None  # none at all
    (tmp_path / "bare.npy.json").write_text("[1, 2]")
    with pytest.raises(im.FormatError, match="bare.npy.json: expected a JSON object"):
        im.read_generator(tmp_path / "bare.npy")
