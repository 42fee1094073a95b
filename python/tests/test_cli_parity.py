"""Walks the indentmap program's subcommands and options (its --help) against cli_parity.PARITY: every
one has a Python counterpart that exists, or a stated reason; no entry names what the program lacks."""
import inspect
import os
import re
import subprocess

import pytest

import indentmap as im
from indentmap import cli_parity
from indentmap.cli_parity import NOT_YET, PARITY, Python, Reason

OPTION = re.compile(r"(?<![\w-])--([a-z][a-z0-9]*(?:-[a-z0-9]+)*)")
NOT_OPTIONS = {"help", "version"}


def help_text(cli, *command):
    return subprocess.run([cli, *command, "--help"], capture_output=True, check=True).stdout.decode("utf-8")


def help_options(text):
    """The long options of a --help text: those of its usage lines (up to the first blank line; a line
    that sends to another command's --help excepted) and of its option lines (indented, starting --)."""
    found, usage = set(), True
    for line in text.splitlines():
        if usage:
            if not line.strip():
                usage = False
            elif "--help)" not in line:
                found |= set(OPTION.findall(line))
        elif re.match(r"^ {1,4}--", line):
            found |= set(OPTION.findall(line))
    return found - NOT_OPTIONS


def walk(cli):
    """{command: set of options}, commands as 'indent' and modes as 'render view3d'."""
    top = help_text(cli)
    assert "commands:" in top, top
    commands = re.findall(r"^  ([a-z][a-z0-9-]*) ", top.split("commands:", 1)[1], re.M)
    assert len(commands) >= 5, top
    walked = {}
    for command in commands:
        text = help_text(cli, command)
        walked[command] = help_options(text)
        # modes: 'usage: indentmap render contact FORCE...'; one with its own --help is walked on its own
        for mode in sorted(set(re.findall(rf"indentmap {re.escape(command)} ([a-z][a-z0-9-]*)\b", text))):
            walked[f"{command} {mode}"] = (help_options(help_text(cli, command, mode))
                                           if f"{command} {mode} --help" in text else set())
    return walked


@pytest.fixture(scope="module")
def walked(cli):
    return walk(cli)


def cli_keys(walked):
    keys = set()
    for command, options in walked.items():
        keys.add(command)
        keys |= {f"{command} --{option}" for option in options}
    return keys


def test_help_parsing_finds_what_it_should(walked):
    """The walk itself: known subcommands, modes and options are found (a broken parse fails here)."""
    assert {"surface", "indent", "render", "run", "theory", "info", "formats", "render view3d",
            "render contact"} <= set(walked)
    assert {"hardness", "approach", "load", "out", "quality", "adhesion-work"} <= walked["indent"]
    assert {"backend"} <= walked["info"]  # from its usage line only
    assert "force" not in walked["render"]  # view3d's, named on render's usage line that sends there
    assert not walked["formats"]


def test_every_cli_option_has_a_python_decision(walked):
    missing = sorted(cli_keys(walked) - set(PARITY))
    assert not missing, ("CLI subcommands or options with no entry in indentmap/cli_parity.py's PARITY "
                         f"(name a Python counterpart or a reason): {missing}")


def test_no_entry_names_what_the_cli_lacks(walked):
    keys = cli_keys(walked)
    stale = sorted(key for key in PARITY if key not in keys
                   and not (key.split(" ")[0] in cli_parity.OPTIONAL_COMMANDS
                            and key.split(" ")[0] not in walked))
    assert not stale, f"PARITY entries for subcommands or options the CLI no longer has: {stale}"


def resolve(target):
    thing = im
    for part in target.split("."):
        assert hasattr(thing, part), f"indentmap has no {target} ({part})"
        thing = getattr(thing, part)
    return thing


@pytest.mark.parametrize("key", sorted(PARITY))
def test_entry_is_a_counterpart_or_a_reason(key):
    entry = PARITY[key]
    assert isinstance(entry, (Python, Reason)), f"{key}: {entry!r}"
    if isinstance(entry, Reason):
        assert entry.text.strip(), f"{key}: an empty reason"
        return
    thing = resolve(entry.target)
    if entry.parameter is not None:
        parameters = inspect.signature(thing).parameters
        assert entry.parameter in parameters, f"{key}: {entry.target} has no parameter {entry.parameter}"
        assert parameters[entry.parameter].kind not in (inspect.Parameter.VAR_KEYWORD,
                                                        inspect.Parameter.VAR_POSITIONAL)


def test_help_agrees_with_the_option_tables_in_the_source(walked):
    """What --help lists is what getopt accepts (src/cli/*.c's struct option tables): an option the
    program takes but does not list would escape the walk."""
    source = os.environ.get("IM_SOURCE_DIR")
    if not source:
        pytest.skip("IM_SOURCE_DIR is not set (run through ctest)")
    with open(os.path.join(source, "src", "cli", "cli.h"), encoding="utf-8") as f:
        shared = re.search(r"#define CLI_SURFACE_FILE_OPTIONS((?:.*\\\n)*.*)", f.read())  # the lines it continues
    assert shared, "cli.h: no CLI_SURFACE_FILE_OPTIONS"
    files = {"surface": "surface.c", "theory": "theory.c", "indent": "indent.c", "render": "render.c",
             "render view3d": "render_view3d.c", "run": "run.c", "info": "info.c", "mpi-indent": "mpi_indent.c"}
    for command, name in files.items():
        if command not in walked:
            continue
        with open(os.path.join(source, "src", "cli", name), encoding="utf-8") as f:
            text = f.read()
        table = re.search(r"struct option \w+\[\] = \{(.*?)\{0, 0, 0, 0\}", text, re.S)
        assert table, f"{name}: no struct option table"
        entries = table.group(1).replace("CLI_SURFACE_FILE_OPTIONS", shared.group(1))
        accepted = set(re.findall(r'\{"([a-z0-9-]+)"', entries)) - NOT_OPTIONS
        assert accepted == walked[command], (f"{command}: getopt takes {sorted(accepted - walked[command])} "
                                             f"unlisted; --help lists {sorted(walked[command] - accepted)} "
                                             "that getopt does not take")


def test_not_yet_is_documented():
    """docs/python.md's "What Python cannot do yet" lists each NOT_YET entry and states their count."""
    source = os.environ.get("IM_SOURCE_DIR")
    if not source:
        pytest.skip("IM_SOURCE_DIR is not set (run through ctest)")
    with open(os.path.join(source, "docs", "python.md"), encoding="utf-8") as f:
        doc = f.read()
    assert "## What Python cannot do yet" in doc
    section = doc.split("## What Python cannot do yet", 1)[1].split("\n## ", 1)[0]
    pending = cli_parity.not_yet()
    assert f"{len(pending)} " in section, f"the section should state the count, {len(pending)}"
    for key in pending:
        assert f"`{key}`" in section, f"docs/python.md does not list `{key}` under What Python cannot do yet"


def test_quality_keyword_matches_the_presets(rough64):
    """Indentation(quality=...) is indent --quality: the preset's tolerance; tol overrides it."""
    assert im._core.quality_tolerance("draft") == 1e-5
    assert im._core.quality_tolerance("publication") == 1e-9
    with pytest.raises(im.InvalidArgument):
        im._core.quality_tolerance("best")
    draft = im.indent(rough64, approaches=[1.0, 2.0], quality="draft")
    publication = im.indent(rough64, approaches=[1.0, 2.0], quality="publication")
    same = im.indent(rough64, approaches=[1.0, 2.0], quality="draft", tol=1e-9)
    assert (publication["load"] == same["load"]).all()
    assert not (draft["load"] == publication["load"]).all()
    assert (publication["iterations"] >= draft["iterations"]).all()
