"""Shared fixtures of the Python module's tests: the project's data files."""
import os
import pathlib

import pytest

DATA = pathlib.Path(os.environ.get("TPF_DATA_DIR", pathlib.Path(__file__).parents[2] / "data"))


@pytest.fixture(scope="session")
def data():
    return DATA
