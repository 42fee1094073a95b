"""Scenes (the library's scene.h)."""
from . import _core


def run_scene(path, resume=False, quiet=True):
    """Runs a scene file as ``indentmap run`` does (without the GIL) and returns its output folder.
    Stage lines go to stderr unless ``quiet``; ``resume`` reuses results kept on disk."""
    return _core.run_scene(path, resume=resume, quiet=quiet)
