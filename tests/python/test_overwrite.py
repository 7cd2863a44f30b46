"""sweep(output=DIR) never replaces finished results by accident: the
command line's rule and message, with the Python keywords in place of the
flags. Without overwrite=True or resume=True a sweep into a
folder that holds results is refused (exit code 2) and the files stay as they
are; overwrite=True replaces them; resume=True into a folder without a
journal accepts only this configuration's finished results (and leaves them
untouched) -- the command line's `--resume` rule."""
import os

import pytest

import stickslip

FIRST = dict(lam=[1, 2], realizations=100, seed=1)
SECOND = dict(lam=[3, 4, 5], mu=[1, 2], realizations=100, seed=5)
SECOND_CLI = ["--lambda", "3,4,5", "--mu", "1,2", "--realizations", 100, "--seed", 5]


def snapshot(folder):
    return {name: (folder / name).read_bytes() for name in sorted(os.listdir(folder))}


@pytest.fixture
def finished(tmp_path):
    out = tmp_path / "ow"
    stickslip.sweep(**FIRST, output=str(out))
    return out, snapshot(out)


def test_a_second_sweep_is_refused_like_the_cli(finished, cli):
    out, before = finished
    with pytest.raises(stickslip.Error) as e:
        stickslip.sweep(**SECOND, output=str(out))
    assert e.value.exit_code == 2
    assert snapshot(out) == before  # nothing replaced, no journal left
    message = str(e.value)
    assert f"'{out / 'results.nc'}' already exists (the results of an earlier run)" in message
    assert "overwrite=True" in message and "resume=True" in message
    # The command line refuses the same thing, for the same file and reason.
    p = cli("sweep", *SECOND_CLI, "-o", out, check=False)
    assert p.returncode == 2 and snapshot(out) == before
    theirs = p.stderr.strip().removeprefix("stickslip: error: ")
    assert theirs.split(": add ")[0] == message.split(": pass ")[0]


def test_overwrite_true_replaces(finished):
    out, before = finished
    ds = stickslip.sweep(**SECOND, output=str(out), overwrite=True)
    assert dict(ds.sizes)["mu"] == 2 and ds.attrs["seed"] == 5
    assert snapshot(out) != before
    assert stickslip.open(out).attrs["seed"] == 5


def test_overwrite_true_names_the_earlier_outputs_it_removes(tmp_path):
    # records.csv of an earlier records=True run is not this run's: it goes,
    # and a UserWarning names it (the CLI's note); a plain replacement warns
    # of nothing.
    out = tmp_path / "rec"
    stickslip.sweep(**FIRST, output=str(out), records=True)
    with pytest.warns(UserWarning) as caught:
        stickslip.sweep(**FIRST, output=str(out), overwrite=True)
    assert [str(w.message) for w in caught] == [
        f"removed '{out / 'records.csv'}': it was an earlier run's, which this run does not write"]
    assert not (out / "records.csv").exists()
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("error", UserWarning)
        stickslip.sweep(**FIRST, output=str(out), overwrite=True)


def test_resume_into_another_configurations_results_is_refused(finished):
    out, before = finished
    with pytest.raises(stickslip.Error, match="another configuration") as e:
        stickslip.sweep(**SECOND, output=str(out), resume=True)
    assert e.value.exit_code == 2
    assert snapshot(out) == before


def test_resume_onto_this_configurations_results_leaves_them(finished):
    out, before = finished
    ds = stickslip.sweep(**FIRST, output=str(out), resume=True)
    assert snapshot(out) == before
    assert ds.identical(stickslip.open(out))


def test_a_folder_without_results_is_fine(tmp_path):
    out = tmp_path / "other"
    out.mkdir()
    (out / "notes.txt").write_text("mine")
    stickslip.sweep(**FIRST, output=str(out))
    assert (out / "results.nc").exists() and (out / "notes.txt").read_text() == "mine"


def test_overwrite_must_be_a_bool(tmp_path):
    with pytest.raises(stickslip.Error, match="overwrite") as e:
        stickslip.sweep(**FIRST, output=str(tmp_path / "x"), overwrite="yes")
    assert e.value.exit_code == 2
