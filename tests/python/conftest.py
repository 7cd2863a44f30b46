"""Fixtures of the Python package's tests. ctest runs them with PYTHONPATH at
the build tree's python/ folder and STICKSLIP_CLI at the command-line tool,
so that every Python result can be compared with the CLI's."""
import os
import signal
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


@pytest.fixture(scope="session")
def ctrl_c():
    """Sends SIGINT to a running script that exits 42 after printing
    "KeyboardInterrupt"; fails unless it does so within `timeout` seconds.
    Returns its stdout."""
    def send(p, what, timeout=60):
        p.send_signal(signal.SIGINT)
        try:
            stdout, stderr = p.communicate(timeout=timeout)
        except subprocess.TimeoutExpired:
            p.kill()
            pytest.fail(f"Ctrl-C did not stop {what}")
        assert p.returncode == 42, (p.returncode, stderr[-2000:])
        assert "KeyboardInterrupt" in stdout
        return stdout
    return send
