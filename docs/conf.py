"""Sphinx configuration of the quadric-contact documentation.

Build: ``pip install ".[docs]" && sphinx-build -W docs docs/_build/html`` (warnings are
errors and every cross-reference is checked: ``nitpicky``).  The notebooks in
``notebooks/`` are executed by myst-nb at build time and cached in
``docs/_build/.jupyter_cache`` (the first build runs them, and the numba kernels compile on
their first use: a few minutes; later builds reuse the outputs of unchanged notebooks).
Pages generated at build time (the errata from the registry, the copied notebooks, the API
stubs) are written by ``docs/_ext/qc_docs.py`` and are not kept in git.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
sys.path.insert(0, str(ROOT / "src"))
sys.path.insert(0, str(DOCS / "_ext"))
# the notebook kernels import this checkout's package, as the test suite's do
os.environ["PYTHONPATH"] = os.pathsep.join([str(ROOT / "src"), *filter(None, [os.environ.get("PYTHONPATH")])])

import quadric_contact  # noqa: E402

project = "quadric-contact"
author = "the quadric-contact authors"
copyright = "2026, the quadric-contact authors"
release = quadric_contact.__version__
version = release

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "numpydoc",
    "myst_nb",
    "qc_docs",
]

root_doc = "index"
# root-sign patterns such as ---+ and -0++ are text, not dashes to be typeset
smartquotes = False
exclude_patterns = [
    "_build",
    "_generated",
    "benchmarks/*.md",
    "**.ipynb_checkpoints",
    "gallery/make_gallery.py",
    "README.md",
]
source_suffix = {".rst": "restructuredtext", ".md": "myst-nb", ".ipynb": "myst-nb"}
suppress_warnings: list[str] = []

# -- cross-references: every one is checked ------------------------------------------------
nitpicky = True
# The site is built offline (no intersphinx inventories): names from Python's standard
# library and from the dependencies cannot be linked, and are the only ones let through.
_EXTERNAL = (
    r"(fractions|numbers|decimal|typing|collections|enum|pathlib|argparse|concurrent|types"
    r"|ast|numpy|np|sympy|flint|mpmath|dask|distributed|matplotlib|hypothesis|numba|tomllib|abc)"
)
nitpick_ignore_regex = [
    # annotations written as strings (``from __future__ import annotations``) in attribute types
    (r"py:class", r"'.*"),
    (r"py:.*", _EXTERNAL + r"(\..*)?"),
    (
        r"py:.*",
        r"(int|float|str|bool|bytes|complex|object|tuple|list|dict|set|frozenset|None"
        r"|type|Callable|Iterable|Iterator|Sequence|Mapping|Any|Path|Fraction|ndarray|array-like"
        r"|matrix-like|optional|default|callable|ValueError|TypeError|ImportError|KeyError"
        r"|FileNotFoundError|Exception|IntEnum|StrEnum|Enum|NamedTuple)",
    ),
]

# -- API reference ---------------------------------------------------------------------------
autosummary_generate = True
autosummary_imported_members = False
autodoc_typehints = "none"  # numpydoc's Parameters and Returns say the types
autodoc_member_order = "bysource"
# members defined in each module (a name re-exported by a package is documented where it is
# defined, once); the public API page links to them
autodoc_default_options = {
    "members": True,
    "undoc-members": True,
    "no-value": True,
    "show-inheritance": True,
    "ignore-module-all": True,
}
templates_path = ["_templates"]
numpydoc_show_class_members = False
numpydoc_xref_param_type = False
numpydoc_validation_checks: set[str] = set()

# -- notebooks -------------------------------------------------------------------------------
nb_execution_mode = "cache"
nb_execution_cache_path = str(DOCS / "_build" / ".jupyter_cache")
nb_execution_timeout = 1800
nb_execution_raise_on_error = True
nb_execution_show_tb = True
nb_merge_streams = True
# stderr carries the kernels' one-line compile notice, which depends on the state of numba's
# cache when the notebook ran, not on the notebook
nb_output_stderr = "remove"
myst_enable_extensions = ["dollarmath", "colon_fence", "deflist"]
myst_heading_anchors = 3

# -- HTML ------------------------------------------------------------------------------------
html_theme = "pydata_sphinx_theme"
html_title = "quadric-contact"
html_static_path = ["_static"]
html_theme_options = {
    "navigation_with_keys": False,
    "show_toc_level": 2,
    "secondary_sidebar_items": ["page-toc"],
    "header_links_before_dropdown": 4,
}
# the section navigation where a section has pages of its own (the API reference, the
# notebooks); the single pages have none to show
html_sidebars = {
    "*": [],
    "api/**": ["sidebar-nav-bs"],
    "api/index": ["sidebar-nav-bs"],
    "notebooks/*": ["sidebar-nav-bs"],
    "notebooks": ["sidebar-nav-bs"],
}
html_show_sourcelink = False
html_favicon = "_static/favicon.svg"
# the theme's colour mode when the reader has not chosen one (its default, empty, makes the
# theme's script log an error on every page)
html_context = {"default_mode": "light"}
