"""The book's Python chapter (book/src/python.md) is a doctest: its examples
run from the repository's root and print what the page shows."""

import doctest
import re

import pytest

from conftest import ROOT


def test_book_python_chapter(monkeypatch):
    pytest.importorskip("sympy")
    monkeypatch.chdir(ROOT)
    result = doctest.testfile(
        str(ROOT / "book" / "src" / "python.md"),
        module_relative=False,
        optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE,
        verbose=False,
    )
    assert result.attempted >= 15
    assert result.failed == 0


def test_book_dask_snippet_runs_as_written(monkeypatch):
    """The chapter's Dask snippet (a text block: it names a real cluster),
    run as written on a local cluster instead: every name it uses is
    imported or defined in it."""
    pytest.importorskip("dask.distributed")
    monkeypatch.chdir(ROOT)
    page = (ROOT / "book" / "src" / "python.md").read_text(encoding="utf-8")
    blocks = re.findall(r"```text\n(from dask.distributed import Client\n.*?)```", page, re.S)
    assert len(blocks) == 1
    address = 'Client("tcp://scheduler.example.org:8786")'
    assert blocks[0].count(address) == 1
    code = blocks[0].replace(address, "Client(processes=False, n_workers=2, threads_per_worker=1)")
    names = {}
    try:
        exec(compile(code, "book/src/python.md (Dask)", "exec"), names)  # noqa: S102
    finally:
        if "client" in names:
            names["client"].close()
    flips = names["flips"]
    assert flips.shape == (40, 40) and flips.dtype == bool
    # the lower rod flips over from some starting angles and not from others
    assert flips.any() and not flips.all()
    assert not flips[19:21, 19:21].any()  # near the bottom it does not


def test_one_install_command_in_the_readme_the_book_and_ci():
    """A newcomer installs with one command (one build of the wheel), the
    one CI runs: `pip install './python[test]'`."""
    command = "pip install './python[test]'"
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    section = readme[readme.index("\n## Python\n"):]
    section = section[:section.index("\n## ", 1)]
    book = (ROOT / "book" / "src" / "python.md").read_text(encoding="utf-8")
    for page in (section, book):
        block = re.search(r"```sh\n(.*?)```", page, re.S).group(1)
        installs = [line.split("#")[0].strip() for line in block.splitlines() if "pip install" in line]
        assert installs == [command]
    ci = (ROOT / ".ci" / "run").read_text(encoding="utf-8")
    assert [line.split("/bin/")[-1] for line in ci.splitlines() if "install --quiet './python" in line] == [
        "pip\" install --quiet './python[test]'"]
