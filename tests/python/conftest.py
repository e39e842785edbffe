"""Where the tests find the project and the program: RY_SOURCE_DIR and RY_BINARY (set by
ctest), else this repository and its build/ryushi."""
import os

import pytest

ROOT = os.environ.get("RY_SOURCE_DIR") or os.path.normpath(
    os.path.join(os.path.dirname(__file__), "..", ".."))


@pytest.fixture
def root():
    return ROOT


@pytest.fixture
def binary():
    return os.environ.get("RY_BINARY") or os.path.join(ROOT, "build", "ryushi")


@pytest.fixture
def case():
    return lambda name: os.path.join(ROOT, "cases", name)
