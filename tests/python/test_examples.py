"""The examples of examples/python run to their end (the parameter study in its --quick form)."""
import os
import subprocess
import sys


def run_example(root, *args):
    path = os.path.join(root, "examples", "python", args[0])
    r = subprocess.run([sys.executable, path] + list(args[1:]), capture_output=True, text=True,
                       env=dict(os.environ, OMP_NUM_THREADS="1"))
    assert r.returncode == 0, r.stderr
    return r.stdout


def test_parameter_study(root, tmp_path):
    out = run_example(root, "parameter_study.py", "--quick", "--output", str(tmp_path))
    assert out.count("front against Martin & Moyce") == 2
    assert "a/20" in out


def test_read_output(root, tmp_path):
    out = run_example(root, "read_output.py", str(tmp_path / "run"))
    assert "16 particle files" in out and "800 fluid" in out and "fluid mass 125," in out
