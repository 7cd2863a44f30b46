"""Fixtures of the Python package's tests. ctest runs them with PYTHONPATH at
the build tree's python/ folder and STICKSLIP_CLI at the command-line tool,
so that every Python result can be compared with the CLI's."""
import os
import subprocess

import pytest


@pytest.fixture(scope="session")
def cli():
    path = os.environ.get("STICKSLIP_CLI")
    if not path or not os.path.exists(path):
        pytest.fail("STICKSLIP_CLI must name the stickslip executable (ctest sets it)")

    def run(*args, check=True):
        p = subprocess.run([path, *map(str, args)], capture_output=True, text=True)
        if check and p.returncode != 0:
            raise AssertionError(f"stickslip {' '.join(map(str, args))} failed ({p.returncode}): {p.stderr}")
        return p
    return run
