"""The documentation's pages are true: the Python examples of every page in ``docs/`` run as
written and print what the page says (one namespace per page, in order), and the links
between the pages and to the checkout lead somewhere.  The site itself is built and read in
a browser by ``tests/test_docs_site.py``."""

from __future__ import annotations

import doctest
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
PAGES = sorted(DOCS.glob("*.md"))
BLOCK = re.compile(r"^```python\n(.*?)^```", flags=re.S | re.M)


def test_there_are_pages_with_examples():
    with_examples = [p for p in PAGES if BLOCK.search(p.read_text())]
    assert len(with_examples) >= 6, with_examples


@pytest.mark.parametrize("page", [p for p in PAGES if BLOCK.search(p.read_text())], ids=lambda p: p.stem)
def test_the_examples_of_a_page_run_as_written(page):
    parser = doctest.DocTestParser()
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    globs: dict = {}
    for k, block in enumerate(BLOCK.findall(page.read_text())):
        test = parser.get_doctest(block, globs, f"{page.name} block {k + 1}", str(page), 0)
        test.globs = globs  # one namespace for the whole page (get_doctest copies it)
        assert test.examples, f"{page.name} block {k + 1} has no >>> examples"
        runner.run(test, clear_globs=False)
    result = runner.summarize(verbose=False)
    assert result.failed == 0, f"{result.failed} example(s) of {page.name} failed (see the output above)"


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.stem)
def test_relative_links_of_a_page_exist(page):
    links = re.findall(r"\]\(([^)#\s]+)(?:#[^)]*)?\)", page.read_text())
    local = [t for t in links if "://" not in t]
    missing = [t for t in local if not (page.parent / t).exists() and not _copied_notebook(t)]
    assert not missing, missing


def _copied_notebook(target: str) -> bool:
    """``notebooks/NN_name.ipynb`` links to the notebook the site build copies from the
    checkout's ``notebooks/``."""
    return target.startswith("notebooks/") and (ROOT / target).exists()
