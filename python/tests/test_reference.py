"""docs/python-reference.md is made from the docstrings (scripts/python_reference.py): every public name has
its own docstring with an example, and the page in the repository is the one the script writes now."""
import importlib.util
import inspect
import os
import subprocess
import sys

import pytest

import indentmap as im


@pytest.fixture(scope="module")
def source():
    path = os.environ.get("IM_SOURCE_DIR")
    if not path:
        pytest.skip("IM_SOURCE_DIR is not set (run through ctest)")
    return path


@pytest.fixture(scope="module")
def reference(source):
    spec = importlib.util.spec_from_file_location("python_reference",
                                                  os.path.join(source, "scripts", "python_reference.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def own_doc(obj):
    """The object's own docstring: not one inherited from a base class or made up by dataclass."""
    doc = obj.__doc__ if not isinstance(obj, property) else obj.fget.__doc__
    if inspect.isclass(obj) and any(doc is base.__doc__ for base in obj.__mro__[1:]):
        return ""
    return inspect.cleandoc(doc or "")


def test_every_public_name_has_a_docstring_with_an_example(reference):
    names = reference.public_names()
    assert {"indent", "Indentation.step", "Figure.save", "theory.area_ratio", "InvalidArgument", "info"} <= \
        {name for name, _ in names}
    for name, obj in names:
        doc = own_doc(obj)
        assert doc and not doc.startswith(f"{name.split('.')[-1]}("), f"{name} has no docstring of its own"
        assert "Example" in doc, f"{name}'s docstring has no example"


def test_the_page_is_up_to_date(reference, source):
    page = os.path.join(source, "docs", "python-reference.md")
    with open(page, encoding="utf-8") as f:
        assert f.read() == reference.page(), "run scripts/python_reference.py docs/python-reference.md"
    check = subprocess.run([sys.executable, os.path.join(source, "scripts", "python_reference.py"), "--check", page],
                           capture_output=True, text=True)
    assert check.returncode == 0, check.stderr


def test_help_answers_what_a_user_needs():
    text = own_doc(im.indent)
    for word in ("Returns", "Example", "loads", "units"):
        assert word in text, word
