"""The book's Python chapter (book/src/python.md) is a doctest: its examples
run from the repository's root and print what the page shows."""

import doctest
import os

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
