"""Scenes (the library's scene.h)."""
import logging

from . import _core

logger = logging.getLogger("indentmap")


def run_scene(path, resume=False, quiet=False, progress=None, log=None):
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
    for ``resume``."""
    return _core.run_scene(path, resume=resume, quiet=quiet, progress=progress,
                           log=logger.log if log is None else log)
