"""The package as shipped: its type stubs, the README's "From Python" example as printed, and the
T-handle example."""

import pathlib
import re
import runpy
import sys
from importlib import resources

import tumble

ROOT = pathlib.Path(__file__).resolve().parents[2]


def test_stubs_are_shipped():
    stub = resources.files("tumble") / "_tumble.pyi"
    assert stub.is_file()
    text = stub.read_text()
    for name in ("class Scene", "class RigidBody", "class Parameterization", "def integrate",
                 "def ensemble"):
        assert name in text
    assert (resources.files("tumble") / "py.typed").is_file()


def readme_example():
    text = (ROOT / "README.md").read_text()
    section = text.split("\n## From Python\n", 1)[1]
    return re.search(r"```python\n(.*?)```", section, re.S).group(1)


def test_readme_example_runs_as_printed(capsys):
    exec(compile(readme_example(), "README.md (From Python)", "exec"), {"__name__": "__main__"})
    printed = capsys.readouterr().out
    assert "omega(50)" in printed and "failed runs: 0" in printed


def test_t_handle_example(tmp_path, monkeypatch):
    monkeypatch.setattr(sys, "argv", ["tumbling_t_handle.py", str(tmp_path)])
    example = runpy.run_path(str(ROOT / "python" / "examples" / "tumbling_t_handle.py"))
    assert example["main"](str(tmp_path)) >= 2
    assert (tmp_path / "t_handle_omega_py.csv").is_file()


def test_attitude_dispersion_example(tmp_path):
    example = runpy.run_path(str(ROOT / "python" / "examples" / "attitude_dispersion.py"))
    assert example["main"](str(tmp_path), 200) == 0  # no failed run
    assert (tmp_path / "attitude_dispersion_py.csv").is_file()
