"""fracarm.design runs the CLI's verbs in-process: same documents, same files, same errors."""
import filecmp
import json

import pytest

from conftest import cli
from fracarm import design
from fracarm.errors import FracarmError, UsageError


def cli_json(*args):
    st, out, err = cli(*args, "--json")
    assert st == 0, err
    return json.loads(out)


def test_tune_returns_the_cli_document():
    # A plant and specification of seed 001's form with values chosen here.
    kw = dict(K=1.7, T=0.21, lambda_=1.6, wc=2.5, phim=0.8, alpha=0.55)
    got = design.tune("fopi", **kw)
    ref = cli_json("tune", "fopi", "--K", "1.7", "--T", "0.21", "--lambda", "1.6", "--wc", "2.5", "--phim", "0.8",
                   "--alpha", "0.55")
    assert got == ref


def test_lqg_and_armctrl_write_the_cli_files(tmp_path):
    got = design.lqg(exp="D", out=str(tmp_path / "py.json"))
    ref = cli_json("lqg", "--exp", "D", "--out", tmp_path / "cli.json")
    assert got == ref and filecmp.cmp(tmp_path / "py.json", tmp_path / "cli.json", shallow=False)
    for fmt in ("json", "bin"):
        a = design.armctrl("B", str(tmp_path / ("py." + fmt)), format=fmt)
        b = cli_json("armctrl", "--exp", "B", "--out", tmp_path / ("cli." + fmt), "--format", fmt)
        a.pop("out", None), b.pop("out", None)
        assert a == b and filecmp.cmp(tmp_path / ("py." + fmt), tmp_path / ("cli." + fmt), shallow=False)


def test_model_returns_the_cli_document():
    assert design.model("collocated", m2=0.2) == cli_json("model", "collocated", "--m2", "0.2")
    assert design.argv("tune", "fopi", band_lo=1.0) == ["fopi", "--band-lo", "1.0"]


def test_errors_are_the_cli_stderr_line():
    with pytest.raises(UsageError) as e:
        design.tune("fopi", K=1, T=0.2, lambda_=1.5, wc=2, phim=0.8, alpha=0.5, bogus=3)
    st, _, err = cli("tune", "fopi", "--K", "1", "--T", "0.2", "--lambda", "1.5", "--wc", "2", "--phim", "0.8",
                     "--alpha", "0.5", "--bogus", "3")
    assert st == 2 and err.strip() == str(e.value)
    with pytest.raises(FracarmError) as e:
        design.model(model="/nonexistent/m.json")
    st, _, err = cli("model", "--model", "/nonexistent/m.json")
    assert st == 1 and err.strip() == str(e.value)
