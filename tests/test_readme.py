"""The README is true: its Python examples run as written and print what it says,
its quick-start commands are the ones CI runs, and its links lead somewhere."""

from __future__ import annotations

import doctest
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
README = (ROOT / "README.md").read_text()
BLOCKS = re.findall(r"^```python\n(.*?)^```", README, flags=re.S | re.M)


def test_the_readme_has_a_short_tour():
    """The README is the front door: one short tour (the rest is in docs/, tested by
    tests/test_docs_pages.py), written with the top-level names."""
    assert len(BLOCKS) == 1
    statements = [line for line in BLOCKS[0].splitlines() if line.startswith(">>> ")]
    assert 5 <= len(statements) <= 10
    assert "from quadric_contact" not in BLOCKS[0]


def test_the_tour_runs_as_written():
    """Every python block, in order, in one namespace; outputs compared as doctests."""
    parser = doctest.DocTestParser()
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    globs: dict = {}
    for k, block in enumerate(BLOCKS):
        test = parser.get_doctest(block, globs, f"README block {k + 1}", "README.md", 0)
        test.globs = globs  # one namespace for the whole tour (get_doctest copies it)
        assert test.examples, f"README block {k + 1} has no >>> examples"
        runner.run(test, clear_globs=False)
    result = runner.summarize(verbose=False)
    assert result.failed == 0, f"{result.failed} README example(s) failed (see the output above)"


def test_quick_start_commands_are_the_ones_ci_runs():
    assert "    pip install . && quadric-contact simulate\n" in README
    # the test command is the indented line after "Install and run the whole test suite:"
    match = re.search(r"Install and run the whole test suite:\n\n    (.+)\n", README)
    assert match, "the quick start lost its test command"
    command = match.group(1)
    assert command.startswith('pip install ".[test]" && pytest')
    ci = (ROOT / ".ci" / "run").read_text()
    assert f"\n{command}\n" in ci, "`.ci/run` must run exactly the README's test command"


def test_relative_links_exist():
    links = re.findall(r"\]\(([^)#]+)(?:#[^)]*)?\)", README)
    local = [target for target in links if "://" not in target]
    assert local
    missing = [target for target in local if not (ROOT / target).exists()]
    assert not missing, missing
