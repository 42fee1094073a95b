"""Scenes (the library's scene.h)."""
import logging

from . import _core

logger = logging.getLogger("indentmap")


def run_scene(path, resume=False, quiet=False, progress=None, log=None, out=None, wisdom=None, backend="auto"):
    """Runs a scene file as ``indentmap run`` does (without the GIL) and returns its output folder.

    Nothing is printed. The run's log lines go to ``log(level, message)``, by default the ``indentmap``
    logger (``logging.getLogger("indentmap").log``): the stage lines ("table: 51 surfaces: 51 solved, ...")
    at ``logging.INFO``, notices that a kept result is stale or damaged and solved again, or that a stale
    lock was taken over, at ``logging.WARNING``; ``quiet`` drops the stage lines (progress calls still
    come). ``progress``, if given, is called as ``progress(stage, done, total)`` each time a surface of an
    ensemble stage ("table", "histories") finishes, done = 1 .. total (what ``indentmap run`` draws as its
    bar). Callbacks run on the thread that calls them (a solver thread, holding the GIL for the call); one
    that raises stops the run at its next check and its exception is raised here; one may call the library,
    another ``run_scene`` included. ``resume`` reuses results kept on disk. Ctrl-C raises KeyboardInterrupt
    once the run reaches its next check (between solver steps and surfaces), keeping every finished result
    for ``resume``. ``out``, if given, is the output folder instead of the scene's (``run --out``).

    ``wisdom``, a path, is the FFTW wisdom file of the run's solves (``run --wisdom FILE``): read before
    planning, updated after it, plans measured (FFTW_MEASURE). None (default) is ``run --no-wisdom``:
    estimated plans and no file, whatever ``IM_FFTW_WISDOM`` says (the program's default cache is its
    own). A wisdom file that cannot be read or replaced raises ``FileError`` naming it.

    ``backend`` is the OpenGL backend of the scene's frames and panels (``run --backend``): 'auto' (EGL,
    else OSMesa), 'egl' or 'osmesa'; another name raises ``InvalidArgument`` before anything runs.

    Example: ``im.run_scene("scenes/fig4.ini", out="fig4", wisdom="fftw-wisdom")``."""
    return _core.run_scene(path, resume=resume, quiet=quiet, progress=progress,
                           log=logger.log if log is None else log, out=out, wisdom=wisdom, backend=backend)


def run_scene_from_record(record, out=None, resume=False, quiet=False, progress=None, log=None, wisdom=None,
                          backend="auto"):
    """Runs again the scene a run recorded in its ``run.json`` (``indentmap run --from-record``), under
    ``out`` or the scene's output folder, and returns that folder.

    The scene is rebuilt from the record's ``scene_contents`` (the keys its file set, as parsed), so an
    edit of the scene file since does not matter. ``InvalidArgument`` when an input file's SHA-256 is no
    longer the recorded one or the record is of another version, ``FormatError`` for a file that is not a
    scene run's record with its contents (docs/scenes.md, "Provenance"). Python
    runs plan FFTW without wisdom (estimated plans) unless given ``wisdom``: a run whose plans were measured
    is made again to its last bits only with the same wisdom file. The other arguments are ``run_scene``'s.

    Example: ``im.run_scene_from_record("output/fig4/run.json", out="again")``."""
    return _core.run_scene(record, resume=resume, quiet=quiet, progress=progress,
                           log=logger.log if log is None else log, out=out, from_record=True, wisdom=wisdom,
                           backend=backend)


def check_scene(path, out=None, wisdom=None, log=None, from_record=False):
    """What ``run_scene`` would do, told without solving or writing anything (``indentmap run --check``):
    returns the report the program prints (the inputs as read, the solves, the memory and disk estimates
    against this machine's, every output in the order the run writes it, with the members ``resume`` would
    reuse), or raises the error the run would stop with before any work (``InvalidArgument``,
    ``FormatError``, ``FileError``, ``OutOfMemory`` for a scene too large for this machine's memory).
    ``out``, ``wisdom`` and ``from_record`` (``path`` is then a run's ``run.json``) are ``run_scene``'s;
    notices (a kept result damaged and solved again) go to ``log``, by default the ``indentmap`` logger.

    Example: ``print(im.check_scene("scenes/fig2.ini"))``."""
    return _core.check_scene(path, log=logger.log if log is None else log, out=out, from_record=from_record,
                             wisdom=wisdom)
