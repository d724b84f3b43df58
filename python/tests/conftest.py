"""Shared fixtures: the shipped data and the command-line program, for comparisons."""
import json
import os
import subprocess
from pathlib import Path

import pytest

import plumekit


@pytest.fixture(scope="session")
def data():
    return Path(plumekit.data_dir())


@pytest.fixture(scope="session")
def cli():
    """Runs `plumekit ARGS --json` and returns its summary (the program the module was built with)."""
    exe = os.environ.get("PLUMEKIT_EXE")
    if not exe:
        pytest.skip("PLUMEKIT_EXE is not set (ctest sets it)")

    def run(*args):
        out = subprocess.run([exe, *map(str, args), "--json"], capture_output=True, text=True)
        assert out.returncode == 0, out.stderr
        return json.loads(out.stdout)

    return run
