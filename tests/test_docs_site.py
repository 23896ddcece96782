"""The documentation site, built and read as a reader reads it.

The site is built with warnings as errors (``sphinx-build -W``, nitpicky cross-references),
served from a local HTTP server on 127.0.0.1, and opened in headless Chromium (Debian's
``chromium``, driven by Playwright): the index, an API page, a notebook page with its
figures and the gallery render without a console error or a failed request, the search
finds ``transversal_contact``, and every internal link of every page leads to a page and
an anchor that exist.  Screenshots of each page are written to
``docs/_build/screenshots/``.

Slow (the first build executes the notebooks, a few minutes; later builds reuse the cached
outputs): run with ``pytest -m slow tests/test_docs_site.py``.  Needs the ``docs`` extra
(``pip install ".[docs]"``) and Chromium; where Chromium is missing and ``apt-get`` can be
run, the set-up installs Debian's package.
"""

from __future__ import annotations

import functools
import http.server
import os
import shutil
import subprocess
import sys
import threading
from collections.abc import Iterator
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlsplit

import pytest

pytestmark = pytest.mark.slow

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
BUILD = DOCS / "_build"
HTML = BUILD / "html"
SHOTS = BUILD / "screenshots"

PAGES = {
    "index": "index.html",
    "api": "api/generated/quadric_contact.modes.predicates.html",
    "notebook": "notebooks/05_bee_and_tree.html",
    "gallery": "gallery.html",
}


def _chromium() -> str:
    """Debian's chromium, installed with apt-get where it is missing and root may install."""
    for name in ("chromium", "chromium-browser"):
        found = shutil.which(name)
        if found:
            return found
    if shutil.which("apt-get") and hasattr(os, "geteuid") and os.geteuid() == 0:
        env = {**os.environ, "DEBIAN_FRONTEND": "noninteractive"}
        subprocess.run(["apt-get", "update", "-qq"], check=True, env=env, capture_output=True)
        subprocess.run(
            ["apt-get", "install", "-y", "-qq", "chromium"], check=True, env=env, capture_output=True
        )
        found = shutil.which("chromium")
        if found:
            return found
    pytest.skip("Chromium is not installed (apt-get install chromium)")


@pytest.fixture(scope="module")
def site() -> Path:
    pytest.importorskip("sphinx")
    pytest.importorskip("myst_nb")
    pytest.importorskip("pydata_sphinx_theme")
    result = subprocess.run(
        [sys.executable, "-m", "sphinx", "-W", "-b", "html", str(DOCS), str(HTML)],
        cwd=ROOT,
        capture_output=True,
        text=True,
    )
    assert result.returncode == 0, result.stdout[-5000:] + result.stderr[-5000:]
    return HTML


@pytest.fixture(scope="module")
def server(site: Path) -> Iterator[str]:
    class Quiet(http.server.SimpleHTTPRequestHandler):
        def log_message(self, *args: object) -> None:
            pass

    handler = functools.partial(Quiet, directory=str(site))
    httpd = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    thread = threading.Thread(target=httpd.serve_forever, daemon=True)
    thread.start()
    try:
        yield f"http://127.0.0.1:{httpd.server_address[1]}/"
    finally:
        httpd.shutdown()
        httpd.server_close()


@pytest.fixture(scope="module")
def browser(server: str) -> Iterator[object]:
    playwright_api = pytest.importorskip("playwright.sync_api")
    executable = _chromium()
    with playwright_api.sync_playwright() as p:
        chromium = p.chromium.launch(executable_path=executable, args=["--no-sandbox"])
        try:
            yield chromium
        finally:
            chromium.close()


# The one resource of the site that is not in it: MathJax, from its CDN (pages with math).
# The tests run without a network: the request is refused and recorded, and the pages must
# work without it (the formulas then show as TeX).
EXTERNAL_ALLOWED = ("https://cdn.jsdelivr.net/npm/mathjax@",)


class _Reader:
    """A page opened in the browser, with everything it reported.  Requests that leave the
    local server are refused and recorded in ``external``; the console errors they cause
    are not the page's."""

    def __init__(self, browser: object, url: str) -> None:
        self.errors: list[str] = []
        self.failed: list[str] = []
        self.external: list[str] = []
        self.page = browser.new_page(viewport={"width": 1280, "height": 900})  # type: ignore[attr-defined]
        self.page.route("**/*", self._local_only)
        self.page.on("console", self._console)
        self.page.on("pageerror", lambda e: self.errors.append(str(e)))
        self.page.on("requestfailed", lambda r: r.url not in self.external and self.failed.append(r.url))
        self.page.on("response", lambda r: r.status >= 400 and self.failed.append(f"{r.status} {r.url}"))
        self.page.goto(url, wait_until="load")
        self.page.wait_for_load_state("networkidle")

    def _local_only(self, route: object) -> None:
        url = route.request.url  # type: ignore[attr-defined]
        if urlsplit(url).hostname == "127.0.0.1":
            route.continue_()  # type: ignore[attr-defined]
        else:
            self.external.append(url)
            route.abort()  # type: ignore[attr-defined]

    def _console(self, message: object) -> None:
        if message.type != "error":  # type: ignore[attr-defined]
            return
        if message.location.get("url") in self.external:  # type: ignore[attr-defined]
            return
        self.errors.append(message.text)  # type: ignore[attr-defined]

    def check_clean(self) -> None:
        assert not self.errors, self.errors
        assert not self.failed, self.failed
        unexpected = [u for u in self.external if not u.startswith(EXTERNAL_ALLOWED)]
        assert not unexpected, unexpected

    def images(self) -> list[dict]:
        return self.page.eval_on_selector_all(
            "article img",
            "els => els.map(e => ({src: e.currentSrc, width: e.naturalWidth, complete: e.complete}))",
        )

    def screenshot(self, name: str) -> Path:
        SHOTS.mkdir(parents=True, exist_ok=True)
        path = SHOTS / f"{name}.png"
        self.page.screenshot(path=str(path), full_page=False)
        return path

    def close(self) -> None:
        self.page.close()


@pytest.mark.parametrize("name", list(PAGES))
def test_pages_render_without_console_errors(browser, server, name):
    reader = _Reader(browser, server + PAGES[name])
    try:
        assert reader.page.title(), "a page without a title"
        assert reader.page.locator("article h1").count() >= 1, "a page without a heading"
        images = reader.images()
        broken = [i["src"] for i in images if not (i["complete"] and i["width"] > 0)]
        assert not broken, broken
        if name == "notebook":
            # the notebook rendered with its outputs: code cells, their text and their figures
            assert reader.page.locator("div.cell_output").count() >= 5
            assert len(images) >= 3, images
            reader.page.locator("div.cell_output img").first.scroll_into_view_if_needed()
            reader.screenshot("notebook-figure")
        if name == "gallery":
            sources = [i["src"] for i in images]
            assert sum(s.endswith(".png") for s in sources) >= 9, sources
            assert any(s.endswith(".gif") for s in sources), sources
        if name == "api":
            anchor = "dt#quadric_contact\\.modes\\.predicates\\.transversal_contact"
            assert reader.page.locator(anchor).count() == 1
        reader.page.evaluate("window.scrollTo(0, 0)")
        shot = reader.screenshot(name)
        assert shot.stat().st_size > 10_000
        reader.check_clean()
    finally:
        reader.close()


def test_search_finds_transversal_contact(browser, server):
    reader = _Reader(browser, server + "search.html?q=transversal_contact")
    try:
        reader.page.wait_for_selector("#search-results li", timeout=60_000)
        hits = reader.page.locator("#search-results li").all_inner_texts()
        assert any("transversal_contact" in h for h in hits), hits[:10]
        reader.screenshot("search")
        reader.check_clean()
    finally:
        reader.close()


class _Anchors(HTMLParser):
    def __init__(self) -> None:
        super().__init__()
        self.ids: set[str] = set()
        self.links: list[str] = []

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        values = dict(attrs)
        for key in ("id", "name"):
            if values.get(key):
                self.ids.add(values[key] or "")
        if tag == "a" and values.get("href"):
            self.links.append(values["href"] or "")
        if tag in ("img", "script") and values.get("src"):
            self.links.append(values["src"] or "")
        if tag == "link" and values.get("href"):
            self.links.append(values["href"] or "")


def test_internal_links_resolve(site):
    parsed: dict[Path, _Anchors] = {}

    def read(path: Path) -> _Anchors:
        if path not in parsed:
            reader = _Anchors()
            reader.feed(path.read_text(errors="replace"))
            parsed[path] = reader
        return parsed[path]

    # the pages of the site (``_static`` holds the theme's templates, not pages)
    pages = sorted(p for p in site.rglob("*.html") if "_static" not in p.relative_to(site).parts)
    assert len(pages) > 50
    broken = []
    for page in pages:
        for href in read(page).links:
            parts = urlsplit(href)
            if parts.scheme or parts.netloc or href.startswith(("mailto:", "javascript:", "data:")):
                continue
            path_part, fragment = parts.path, parts.fragment
            target = (page.parent / unquote(path_part)).resolve() if path_part else page
            if target.is_dir():
                target = target / "index.html"
            if not target.exists():
                broken.append(f"{page.relative_to(site)} -> {href}")
                continue
            if fragment and target.suffix == ".html" and unquote(fragment) not in read(target).ids:
                broken.append(f"{page.relative_to(site)} -> {href} (no such anchor)")
    assert not broken, broken[:40]
