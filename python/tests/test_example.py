"""docs/python_example.py runs from start to end."""
import os
import subprocess
import sys

from conftest import BIN, SRC


def test_notebook_example_runs(tmp_path):
    p = subprocess.run([sys.executable, os.path.join(SRC, "docs", "python_example.py"), BIN, str(tmp_path)],
                       capture_output=True, text=True)
    assert p.returncode == 0, p.stdout + p.stderr
    assert "gain_error" in p.stdout and (tmp_path / "report.html").exists() and (tmp_path / "resonance.json").exists()
