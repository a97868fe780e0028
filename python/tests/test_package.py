"""The package as shipped: its type stubs, the README's "From Python" examples as printed, and the
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
                 "def ensemble", "def add_event", "class EventState"):
        assert name in text
    assert (resources.files("tumble") / "py.typed").is_file()


def readme_examples():
    text = (ROOT / "README.md").read_text()
    section = text.split("\n## From Python\n", 1)[1].split("\n## ", 1)[0]
    return re.findall(r"```python\n(.*?)```", section, re.S)


def test_readme_examples_run_as_printed(capsys):
    examples = readme_examples()
    assert len(examples) == 2
    for k, code in enumerate(examples):
        exec(compile(code, f"README.md (From Python, example {k + 1})", "exec"),
             {"__name__": "__main__"})
    printed = capsys.readouterr().out
    assert "omega(50)" in printed and "failed runs: 0" in printed
    assert "impacts at 1.0096, 3.0289 s; 2 events" in printed  # sqrt(2 h / g), 3 sqrt(2 h / g)


def test_t_handle_example(tmp_path, monkeypatch):
    monkeypatch.setattr(sys, "argv", ["tumbling_t_handle.py", str(tmp_path)])
    example = runpy.run_path(str(ROOT / "python" / "examples" / "tumbling_t_handle.py"))
    assert example["main"](str(tmp_path)) >= 2
    assert (tmp_path / "t_handle_omega_py.csv").is_file()


def test_attitude_dispersion_example(tmp_path):
    example = runpy.run_path(str(ROOT / "python" / "examples" / "attitude_dispersion.py"))
    assert example["main"](str(tmp_path), 200) == 0  # no failed run
    assert (tmp_path / "attitude_dispersion_py.csv").is_file()
