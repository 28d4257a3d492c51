"""The Python examples (examples/python at the repository root) run to completion."""

import os
import subprocess
import sys

import pytest

EXAMPLES = os.path.join(os.path.dirname(__file__), "..", "..", "..", "examples", "python")


def run(name, *args, cwd=None):
    path = os.path.abspath(os.path.join(EXAMPLES, name))
    done = subprocess.run([sys.executable, path, *args], capture_output=True, text=True, timeout=300, cwd=cwd)
    assert done.returncode == 0, f"{name} failed:\n{done.stdout}\n{done.stderr}"
    return done.stdout


def test_pyramid():
    out = run("pyramid.py", "--seconds", "1")
    assert "steps/s" in out and "largest drift" in out


def test_ragdoll():
    out = run("ragdoll.py", "--seconds", "1")
    assert "stays connected: yes" in out


def test_tumbling_handle(tmp_path):
    pytest.importorskip("matplotlib")
    out_png = tmp_path / "handle_omega.png"
    run("tumbling_handle.py", "--seconds", "3", "--out", str(out_png))
    assert out_png.stat().st_size > 0
