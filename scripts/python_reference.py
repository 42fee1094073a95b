#!/usr/bin/env python3
"""Writes docs/python-reference.md, the Python package's reference, from its docstrings.

    PYTHONPATH=BUILD/python python3 scripts/python_reference.py docs/python-reference.md

With --check it writes nothing and exits 1 when the page differs from what it would write. Public names:
the package's ``__all__`` and the public functions of ``indentmap.theory``, with the public methods and
properties of each class. python/tests/test_reference.py runs it and also asks every public name for a
docstring with an example.
"""
import argparse
import inspect
import os
import sys

import indentmap

HEADER = """# indentmap's Python package: reference

Generated from the docstrings by `scripts/python_reference.py` (do not edit; `python/tests/test_reference.py`
fails when this page is out of date). The guide is [python.md](python.md); `help(im.NAME)` shows the same
text in Python.

"""


def is_exception(obj):
    return inspect.isclass(obj) and issubclass(obj, BaseException)


def public_members(cls):
    """(name, member) of a class's own public methods and properties, in the order they are defined."""
    members = []
    for name, member in vars(cls).items():
        if name.startswith("_"):
            continue
        if inspect.isfunction(member) or isinstance(member, (classmethod, staticmethod, property)):
            members.append((name, getattr(cls, name)))
    return members


def public_names():
    """(qualified name, object) of every public function, class, method and property, as documented."""
    names = []
    for name in indentmap.__all__:
        obj = getattr(indentmap, name)
        if inspect.ismodule(obj):
            names += [(f"{name}.{n}", f) for n, f in vars(obj).items()
                      if inspect.isfunction(f) and not n.startswith("_") and f.__module__ == obj.__name__]
            continue
        names.append((name, obj))
        if inspect.isclass(obj) and not is_exception(obj):
            names += [(f"{name}.{n}", m) for n, m in public_members(obj)]
    return names


def signature(name, obj):
    if is_exception(obj):
        bases = ", ".join(b.__name__ for b in obj.__bases__)
        return f"exception {name}({bases})"
    if isinstance(obj, property):
        return f"property {name}"
    try:
        return f"{name}{inspect.signature(obj)}"
    except (TypeError, ValueError):
        return name


def section(name, obj):
    doc = inspect.getdoc(obj) or ""
    return f"## `{name}`\n\n```\n{signature(name, obj)}\n```\n\n{doc}\n"


def page():
    return HEADER + "\n".join(section(name, obj) for name, obj in public_names())


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("page", help="the Markdown file (docs/python-reference.md)")
    parser.add_argument("--check", action="store_true", help="exit 1 if the file is not up to date")
    args = parser.parse_args()
    text = page()
    if args.check:
        with open(args.page, encoding="utf-8") as f:
            if f.read() != text:
                sys.exit(f"{args.page} is out of date: run scripts/python_reference.py {args.page}")
        return
    with open(args.page + ".tmp", "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(args.page + ".tmp", args.page)


if __name__ == "__main__":
    main()
