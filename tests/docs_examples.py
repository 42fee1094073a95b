#!/usr/bin/env python3
"""The examples of README.md and docs/*.md run as written, as a new user copies them (findings DA10).

What counts as an example: a command line in a fenced code block (```sh or ```) that starts with
`indentmap`, `build/indentmap`, `mpirun`, or a Python program run on an `examples/` script, and an INI
block that is a whole scene (it starts with [scene]; run as `indentmap run NAME.ini`). Not examples:
docs/benchmarks.md and docs/findings-recheck.md (records of past measurements, commands of their day),
blocks of output and of signatures (docs/python-reference.md), templates in indented blocks
(`mpirun -n K ...`), and the set-up commands (scripts/demo.sh, scripts/test.sh, scripts/setup.sh, cmake,
cc, pip, venv): they build and install, which the tests install, install_pip and install_wheel do.

Each document runs in a scratch folder of its own, its examples in the order written (a later one reads
what an earlier one wrote), each through bash with `build/` a link to the build folder and that folder on
PATH (for the docs' bare `indentmap`), and `scenes/` and `examples/` copies of the tree's. A file an
example reads that no earlier example writes (the user's own: afm.gsf, tip.csv, force_0001.npy, ...) is
made first as a stand-in: a small synthetic surface, its force and displacement fields, a .gsf of it, a
cone's profile. Each example must exit 0 and write what its text names: every file or folder given to
--out, --png, --psd, --histograms, --frames or `>`, a scene's output folder with run.json and index.html,
and every file name its comment gives (`# ... history.png`) in its output folder.

  docs_examples.py SOURCE BUILD --part=quick   the examples that solve nothing (theory, surface, formats,
                                               info, render on stand-ins): seconds, also under the sanitizers
  docs_examples.py SOURCE BUILD --part=slow    every example (indent, scenes, mpirun where the build has MPI);
                                               grids of 1024² and over only with IM_DOCS_EXAMPLES_LARGE=1
  docs_examples.py SOURCE BUILD --list         the inventory: document:line, slow (it solves) or quick, command,
                                               the files and folders it says it writes
  ... --part=slow README.md:91[,...]           those examples alone (stand-ins for the files they read)
exit 1 naming each failing example (document:line, the command, its exit status or the missing output); 77
(skipped) where no OpenGL context opens, unless IM_REQUIRE_GL=1, as tests/cli_render.sh.
"""
import glob
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
import time

FENCE = re.compile(r"^\s*```(\S*)\s*$")
RECORDS = ("findings-recheck.md", "benchmarks.md")
# an example's first words (after NAME=VALUE settings)
PROGRAM = re.compile(r"^(build/indentmap|indentmap|mpirun|(/usr/bin/)?python3)$")
SETUP = re.compile(r"^(scripts/|cmake$|cc$|pip$|python3 -m venv)")
# the commands that solve a contact problem (or run a whole program): the slow part
SOLVES = ("indent", "mpi-indent", "run")
LARGEST = 1024  # grids of it and over only with IM_DOCS_EXAMPLES_LARGE=1
OUTPUT_OPTIONS = ("--out", "--png", "--psd", "--histograms", "--frames")
INPUT_EXTENSIONS = (".npy", ".gsf", ".csv", ".spm", ".json", ".ini", ".py")
FIELD_OPTIONS = {"--force": "force", "--contact": "force", "--displacement": "displacement"}
NAMED_OUTPUT = re.compile(r"\b([\w.-]+\.(?:png|gif|csv|json|html|pdf))\b")


class Example:
    def __init__(self, document, line, text, kind):
        self.document, self.line, self.text, self.kind = document, line, text, kind
        self.command, _, self.comment = text.partition(" #")
        self.command = self.command.strip()
        self.words = shlex.split(self.command, comments=True) if kind == "command" else []

    def where(self):
        return "%s:%d" % (self.document, self.line)

    def program_words(self):
        """The words after NAME=VALUE settings and mpirun's -n K."""
        words = [w for w in self.words if not re.match(r"^[A-Z_]+=", w)]
        if words and words[0] == "mpirun":
            words = words[3:] if len(words) > 2 and words[1] == "-n" else words[1:]
        return words

    def subcommand(self):
        words = self.program_words()
        return words[1] if len(words) > 1 and words[0].endswith("indentmap") else None

    def solves(self):
        """A solving subcommand, but `run --check` (which solves and writes nothing)."""
        return self.subcommand() in SOLVES and "--check" not in self.program_words()

    def slow(self):
        return self.kind == "scene" or self.solves() or not self.program_words()[0].endswith("indentmap")

    def needs_mpi(self):
        return self.words and self.words[0] == "mpirun"

    def needs_gwyddion(self):
        return any(path.endswith(".spm") for path, _ in inputs(self))

    def large(self):
        """A grid of 1024² or over: the README's over MPI (4096²: 3.7 GiB; 1024² with adhesion: not done after
        10 min, 4 ranks on 2 cores at load 22-27)."""
        words = self.program_words()
        return "--n" in words and int(words[words.index("--n") + 1]) >= LARGEST

    def needs_python(self):
        return any(w.startswith("PYTHONPATH=build/python") for w in self.words)

    def needs_gpu(self):
        words = self.program_words()
        return "--device" in words and words[words.index("--device") + 1] == "gpu"


def blocks(path):
    """Yields (line of the block's first line, language, [(line, text)]) for each fenced block."""
    language, lines, start = None, [], 0
    with open(path, encoding="utf-8") as stream:
        for number, line in enumerate(stream, 1):
            match = FENCE.match(line)
            if match and language is None:
                language, lines, start = match.group(1), [], number + 1
            elif match:
                yield start, language, lines
                language = None
            elif language is not None:
                lines.append((number, line.rstrip("\n")))


def joined(lines):
    """The block's lines with the continuation lines (a trailing backslash) joined."""
    pending, first = "", 0
    for number, text in lines:
        if not pending:
            first = number
        if text.rstrip().endswith("\\"):
            pending += text.rstrip()[:-1] + " "
            continue
        yield first, pending + text
        pending = ""


def examples(source):
    found = []
    for path in [os.path.join(source, "README.md")] + sorted(glob.glob(os.path.join(source, "docs", "*.md"))):
        document = os.path.relpath(path, source)
        if os.path.basename(path) in RECORDS:
            continue
        for start, language, lines in blocks(path):
            if language == "ini" and lines and lines[0][1].strip() == "[scene]":
                found.append(Example(document, start, "\n".join(text for _, text in lines), "scene"))
            if language not in ("sh", ""):
                continue
            for number, text in joined(lines):
                stripped = text.strip()
                if not stripped or stripped.startswith("#") or SETUP.match(stripped):
                    continue
                words = [w for w in stripped.split() if not re.match(r"^[A-Z_]+=", w)]
                if words and PROGRAM.match(words[0]):
                    found.append(Example(document, number, stripped, "command"))
    return found


def option_values(words, options):
    return [words[i + 1] for i, w in enumerate(words[:-1]) if w in options]


def outputs(example):
    """The files and folders the example says it writes: (path, must be a folder)."""
    words = example.program_words()
    named = [(p, example.subcommand() in SOLVES) for p in option_values(words, ("--out",))]
    named += [(p, False) for p in option_values(words, OUTPUT_OPTIONS[1:4])]
    named += [(p, True) for p in option_values(words, ("--frames",)) if not p.startswith("-")]
    if ">" in example.words:
        named.append((example.words[example.words.index(">") + 1], False))
    return named


def inputs(example):
    """The files the example reads: positional words and option values that name a file (no globs)."""
    words = example.program_words()
    skip = set(option_values(words, OUTPUT_OPTIONS))
    if ">" in example.words:
        skip.add(example.words[example.words.index(">") + 1])
    found = []
    for i, w in enumerate(words[1:], 1):
        if w in skip or w.startswith("-") or "*" in w or not w.endswith(INPUT_EXTENSIONS):
            continue
        field = FIELD_OPTIONS.get(words[i - 1])
        if field is None and example.subcommand() == "render" and words[2] in ("contact", "animate"):
            field = "force"
        found.append((w, field or "surface"))
    return found


class Scratch:
    """A document's scratch folder, with the stand-ins for the user's own files."""

    def __init__(self, root, source, build):
        self.root, self.source, self.build = root, source, build
        os.symlink(build, os.path.join(root, "build"))
        for folder in ("scenes", "examples"):
            shutil.copytree(os.path.join(source, folder), os.path.join(root, folder))
        self.env = dict(os.environ, PATH=build + os.pathsep + os.environ["PATH"], IM_FFTW_WISDOM="")

    def shell(self, command, timeout=3600):
        return subprocess.run(["bash", "-c", command], cwd=self.root, env=self.env, timeout=timeout,
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)

    def stand_ins(self):
        """A 512 x 512 surface (the README's s.npy) solved at one load: what every stand-in is copied from."""
        folder = os.path.join(os.path.dirname(self.root), "stand-in")  # beside the documents' folders: made once
        if not os.path.isdir(folder):
            os.mkdir(folder)
            # the .gsf states its unit, as a scan does: 10 nm pixels
            made = self.shell("build/indentmap surface --n 512 --seed 1 --out ../stand-in/surface.npy && "
                              "build/indentmap surface --n 512 --seed 1 --delta 1e-8 --unit m "
                              "--out ../stand-in/surface.gsf && "
                              "build/indentmap indent ../stand-in/surface.npy --load 1000 --fields "
                              "--out ../stand-in/run")
            if made.returncode != 0:
                raise RuntimeError("the stand-ins could not be made:\n" + made.stdout)
        return folder

    def make_stand_in(self, path, field):
        folder = self.stand_ins()
        target = os.path.join(self.root, path)
        os.makedirs(os.path.dirname(target) or ".", exist_ok=True)
        if path.endswith(".csv"):  # a punch profile: an 80 degree cone, z = r cot 80°, as r, z samples
            with open(target, "w", encoding="utf-8") as stream:
                stream.write("r,z\n" + "".join("%d,%.6f\n" % (r, r * 0.17632698) for r in range(0, 200, 2)))
            return True
        if path.endswith(".spm"):  # an instrument's file (a Nanoscope .spm, also named .di), read by Gwyddion
            shutil.copyfile(os.path.join(self.source, "tests/data/instruments/di-3.di"), target)
            return True
        chosen = {"force": "run/force_0001.npy", "displacement": "run/displacement_0001.npy"}.get(field, "surface.npy")
        if path.endswith(".gsf"):
            chosen = "surface.gsf"
        elif not path.endswith(".npy"):
            return False
        shutil.copyfile(os.path.join(folder, chosen), target)
        return True


def scene_output(text):
    name = re.search(r"^\s*name\s*=\s*(\S+)", text, re.M)
    output = re.search(r"^\s*output\s*=\s*(\S+)", text, re.M)
    return output.group(1) if output else "output/" + name.group(1)


def expected(example, folder):
    """What the example says it writes: (path, whether a folder), its scene file read under folder."""
    if example.kind == "scene":
        return [(scene_output(example.text), True)]
    named, words = outputs(example), example.program_words()
    if example.subcommand() == "run" and example.solves() and "--out" not in words:
        with open(os.path.join(folder, words[-1]), encoding="utf-8") as stream:
            named.append((scene_output(stream.read()), True))
    if example.subcommand() == "indent" and "--out" not in words:
        named.append(("output/indent", True))  # indent's default folder (indent --help)
    return named


def run_one(example, scratch):
    """Runs one example; returns the faults (empty: it passed)."""
    if example.kind == "scene":
        name = re.search(r"^\s*name\s*=\s*(\S+)", example.text, re.M).group(1)
        with open(os.path.join(scratch.root, name + ".ini"), "w", encoding="utf-8") as stream:
            stream.write(example.text + "\n")
        command = "build/indentmap run --quiet %s.ini" % name
    else:
        for path, field in inputs(example):
            if not os.path.exists(os.path.join(scratch.root, path)) and not scratch.make_stand_in(path, field):
                return ["reads %s, which no earlier example writes and which has no stand-in" % path]
        command = example.command
    if example.needs_mpi():
        command = "source %s && %s" % (shlex.quote(os.path.join(scratch.source, "tests/mpi/open_mpi_env.sh")), command)
    done = scratch.shell(command)
    if done.returncode != 0:
        return ["exit %d:\n%s" % (done.returncode, done.stdout[-3000:])]
    faults = []
    for path, folder in expected(example, scratch.root):
        full = os.path.join(scratch.root, path)
        if folder and not os.path.isdir(full):
            faults.append("wrote no folder %s" % path)
        elif not folder and not (os.path.isfile(full) and os.path.getsize(full) > 0):
            faults.append("wrote no %s (or an empty one)" % path)
        elif folder and (example.kind == "scene" or example.subcommand() in SOLVES):
            faults += ["wrote no %s" % os.path.join(path, f) for f in ("run.json", "index.html") + tuple(
                NAMED_OUTPUT.findall(example.comment)) if not os.path.isfile(os.path.join(full, f))]
    return faults


def left_out(example, can):
    """Whether this pass leaves the example out: a slow one in the quick part, or one this build cannot run."""
    return ((example.slow() and not can["slow"]) or (example.needs_mpi() and not can["mpi"])
            or (example.needs_gpu() and not can["gpu"]) or (example.needs_gwyddion() and not can["gwyddion"])
            or (example.needs_python() and not can["python"]) or (example.large() and not can["large"]))


def reads(word, path):
    """Whether a word names path or a file under it (output/mpi_adhesion is not under output/mpi)."""
    return word == path or word.startswith(path.rstrip("/") + "/")


def run_document(found, scratch, can):
    """Runs a document's examples in order; returns (how many ran, their faults)."""
    faults, ran = [], 0
    skipped = []  # what the examples left out write: a later one reading it is left out too
    for example in found:
        if left_out(example, can) or any(reads(w, path) for w in example.words for path, _ in skipped):
            skipped += outputs(example) if example.kind == "command" else []
            continue
        started = time.monotonic()
        problems = run_one(example, scratch)
        ran += 1
        first = example.text.splitlines()[0]
        print("%-26s %6.1f s  %s" % (example.where(), time.monotonic() - started, first), flush=True)
        faults += ["%s: %s: %s" % (example.where(), first, p) for p in problems]
    return ran, faults


def gl_context(build):
    text = subprocess.run([os.path.join(build, "indentmap"), "info"], stdout=subprocess.PIPE, text=True).stdout
    return "render backend: unavailable" not in text


def gwyddion_built(build):
    text = subprocess.run([os.path.join(build, "indentmap"), "formats"], stdout=subprocess.PIPE, text=True).stdout
    return "Gwyddion's file modules" in text


def mpi_built(build):
    text = subprocess.run([os.path.join(build, "indentmap"), "--help"], stdout=subprocess.PIPE, text=True).stdout
    return "mpi-indent" in text and shutil.which("mpirun") is not None


def main(argv):
    if len(argv) not in (4, 5) or argv[3] not in ("--part=quick", "--part=slow", "--list"):
        sys.stderr.write("usage: docs_examples.py SOURCE BUILD --part=quick|--part=slow|--list [DOCUMENT:LINE]\n")
        return 2
    source, build, mode = os.path.abspath(argv[1]), os.path.abspath(argv[2]), argv[3]
    found = examples(source)
    if len(argv) == 5:  # those examples alone: what the ones before them would write, stand-ins make
        found = [e for e in found if e.where() in argv[4].split(",")]
    if mode == "--list":
        for example in found:
            writes = " ".join(path + ("/" if folder else "") for path, folder in expected(example, source))
            print("%-26s %-5s %s\n%33s writes: %s" % (example.where(), "slow" if example.slow() else "quick",
                                                       example.text.splitlines()[0], "", writes or "(standard output)"))
        return 0
    if not gl_context(build) and os.environ.get("IM_REQUIRE_GL") != "1":
        print("SKIPPED: no OpenGL context (indentmap info): the examples draw their figures with GL")
        return 77  # as tests/cli_render.sh decides; scripts/test.sh sets IM_REQUIRE_GL=1
    can = {"slow": mode == "--part=slow", "mpi": mpi_built(build), "gwyddion": gwyddion_built(build),
           # the GPU engine where it is built and a device opens, as tests/cli_device.sh decides (CMake's IM_HAVE_GPU)
           "gpu": os.environ.get("IM_HAVE_GPU") == "1",
           "python": os.path.isdir(os.path.join(build, "python", "indentmap")),  # built where numpy is found
           "large": os.environ.get("IM_DOCS_EXAMPLES_LARGE") == "1"}
    faults, ran = [], 0
    with tempfile.TemporaryDirectory(prefix="docs_examples.") as scratches:
        for document in dict.fromkeys(e.document for e in found):
            root = os.path.join(scratches, document.replace("/", "_"))
            os.mkdir(root)
            count, problems = run_document([e for e in found if e.document == document], Scratch(root, source, build),
                                           can)
            ran, faults = ran + count, faults + problems
    for fault in faults:
        print("FAIL " + fault)
    print("%d examples run, %d faults" % (ran, len(faults)))
    return 1 if faults or ran == 0 else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
