"""The README's example script runs from start to end (its own asserts check the seeds'
closed form against the hand formulas)."""

import os
import pathlib
import subprocess
import sys

from conftest import ROOT


def test_example_script_runs(tmp_path):
    script = ROOT / "examples" / "python" / "two_link_and_ur5.py"
    env = dict(os.environ, MPLBACKEND="Agg")
    r = subprocess.run([sys.executable, str(script), str(tmp_path)], capture_output=True, text=True,
                       env=env, timeout=600)
    assert r.returncode == 0, r.stderr
    assert "M(θ) by hand" in r.stdout and "UR5 log: 200000 states" in r.stdout
    assert "τ_1 = S_1ᵀ W_1" in r.stdout
    assert (tmp_path / "two_link_run.html").read_text(encoding="utf-8").startswith("<!DOCTYPE")
    assert "M11 =" in r.stdout and "∂τ/∂q =" in r.stdout
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        return
    assert (tmp_path / "two_link_simulation.png").stat().st_size > 1000
