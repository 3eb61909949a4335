# the Python documentation runs as written: every ```python block of docs/python-module.md in
# order (one namespace, as a reader pastes them into one session), and every docstring example
# of the gransim package (doctest)
import doctest
import os
import re
import subprocess

import pytest

import conftest

DOC = os.path.join(conftest.SOURCE_DIR, "docs", "python-module.md")


def python_blocks(path):
    with open(path, encoding="utf-8") as f:
        text = f.read()
    return [(text.count("\n", 0, m.start()) + 2, m.group(1))
            for m in re.finditer(r"```python\n(.*?)```", text, re.S)]


@pytest.fixture
def doc_dir(tmp_path, binary):
    """a folder as the reader's: the scenes beside it and the run read_run reads"""
    import gransim

    os.symlink(os.path.join(conftest.SOURCE_DIR, "scenes"), tmp_path / "scenes")
    # a small tapping run stands in for the teaching scene's (same files, seconds instead)
    (tmp_path / "tiny.toml").write_text(gransim.scene_toml(conftest.tiny_tapping()))
    subprocess.run([binary, "run", "tiny.toml", "--out", "runs/tap_small", "--set", "drive.taps=2",
                    "--quiet"], cwd=tmp_path, check=True, capture_output=True,
                   env={**os.environ, "OMP_NUM_THREADS": "1"})
    return tmp_path


def test_python_module_md_blocks_run(gransim, doc_dir, monkeypatch, capsys):
    monkeypatch.chdir(doc_dir)
    blocks = python_blocks(DOC)
    assert len(blocks) >= 8
    namespace = {}
    for line, code in blocks:
        if "write_movie" in code and not gransim.have_movie:
            continue
        try:
            exec(compile(code, f"{DOC}:{line}", "exec"), namespace)
        except Exception as e:  # the block and its line in the message
            pytest.fail(f"docs/python-module.md block at line {line} fails: {e!r}\n{code}")
    out = capsys.readouterr().out
    assert "drive.gp" in out  # the Errors block caught the misspelt key


def test_docstring_examples_run(gransim, monkeypatch):
    monkeypatch.chdir(conftest.SOURCE_DIR)
    import gransim as package
    import gransim.run_dir

    total = 0
    for module in (package, gransim.run_dir):
        result = doctest.testmod(module, optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
        assert result.failed == 0, module.__name__
        total += result.attempted
    assert total >= 5  # the package docstring's session and the methods' examples
