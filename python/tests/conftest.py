"""Shared by the Python tests: where the scenes are. ctest runs each test file in a process of its
own (python/CMakeLists.txt), with PYTHONPATH at the build's package and TMPDIR a folder of its own."""
from pathlib import Path

import pytest

SOURCE_DIR = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def scenes() -> Path:
    return SOURCE_DIR / "scenes"
