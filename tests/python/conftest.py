"""The Python tests (docs/python.md), run by ctest through pytest with PYTHONPATH=build/python."""
import os
import sys

import pytest

SOURCE = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
EXAMPLES = os.path.join(SOURCE, "examples", "python")
if EXAMPLES not in sys.path:
    sys.path.insert(0, EXAMPLES)


@pytest.fixture
def cube_xml():
    return os.path.join(EXAMPLES, "cube.xml")


@pytest.fixture(autouse=True)
def _in_tmp(tmp_path, monkeypatch):
    """Every test runs in its own folder: outputs never land in the source tree."""
    monkeypatch.chdir(tmp_path)
