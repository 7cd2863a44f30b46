"""One writer per output folder (io/output_lock.hpp), from Python: while the
command-line tool runs a sweep into a folder, stickslip.sweep(output=...)
into it is refused at once with exit code 2 and a message naming the running
sweep's pid; and while a Python sweep writes a folder, the command-line tool
is refused, naming it. Neither refusal touches the running sweep's work."""
import os
import subprocess
import sys
import time

import pytest

import stickslip

LONG = ["--lambda", "1,2,3,4", "--mu", "1,2", "--realizations", "60000", "--block-size", "500",
        "--seed", "3", "--threads", "1"]


def wait_for_lock(folder, process):
    lock = folder / ".stickslip.lock"
    for _ in range(400):
        if lock.exists() and lock.stat().st_size > 0:
            return
        assert process.poll() is None, process.communicate()
        time.sleep(0.05)
    pytest.fail("the first writer never took the lock")


def test_python_is_refused_while_the_cli_writes(tmp_path):
    out = tmp_path / "d"
    first = subprocess.Popen([os.environ["STICKSLIP_CLI"], "sweep", *LONG, "-o", str(out)],
                             stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    try:
        wait_for_lock(out, first)
        t0 = time.monotonic()
        with pytest.raises(stickslip.Error) as e:
            stickslip.sweep(lam=[1], realizations=10, output=str(out), overwrite=True)
        assert e.value.exit_code == 2
        assert f"is in use by stickslip sweep (pid {first.pid} on host " in str(e.value)
        assert time.monotonic() - t0 < 5
        assert first.poll() is None, "the running sweep was disturbed"
    finally:
        first.wait(timeout=120)
    assert first.returncode == 0, first.stderr.read()
    assert (out / "results.nc").exists()


def test_the_cli_is_refused_while_python_writes(tmp_path, cli):
    out = tmp_path / "d"
    script = ("import stickslip; stickslip.sweep(lam=[1, 2, 3, 4], mu=[1, 2], realizations=60000, "
              f"block_size=500, seed=3, threads=1, output={str(out)!r})")
    first = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.DEVNULL,
                             stderr=subprocess.PIPE, text=True)
    try:
        wait_for_lock(out, first)
        p = cli("sweep", "--lambda", "1", "--realizations", "10", "--overwrite", "-o", out, check=False)
        assert p.returncode == 2, p.stderr
        assert f"is in use by stickslip.sweep (Python) (pid {first.pid} on host " in p.stderr
        assert first.poll() is None, "the running sweep was disturbed"
    finally:
        first.wait(timeout=120)
    assert first.returncode == 0, first.stderr.read()
