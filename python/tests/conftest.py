"""Shared paths of the fracarm tests (CTest passes FRAC_SOURCE_DIR, FRAC_BINARY_DIR, FRACARM_CDRIVER)."""
import os
import subprocess

import pytest

SRC = os.environ["FRAC_SOURCE_DIR"]
BIN = os.environ["FRAC_BINARY_DIR"]
FRACDESIGN = os.path.join(BIN, "design_tools", "fracdesign")
HIL_BENCH = os.path.join(BIN, "hil", "hil_bench")
GAP_BENCH = os.path.join(BIN, "bench", "gap-bench")
CDRIVER = os.environ["FRACARM_CDRIVER"]


def cli(*args, cwd=None):
    """Runs fracdesign; (status, stdout, stderr)."""
    p = subprocess.run([FRACDESIGN, *map(str, args)], capture_output=True, text=True, cwd=cwd)
    return p.returncode, p.stdout, p.stderr


@pytest.fixture(scope="session")
def demo_nominal():
    return os.path.join(SRC, "hil", "scenarios", "demo_nominal.json")
