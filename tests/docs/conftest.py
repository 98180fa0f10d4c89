"""Fixtures of the documentation site's browser test: the site built with the README's
command (warnings are errors), served on localhost, and Debian's headless Chromium driven
through playwright (which never downloads a browser of its own here).

The tests that use them are marked ``docs`` and run with ``-m docs`` or ``--rundocs``; each
fixture skips with its reason when Sphinx, playwright or ``/usr/bin/chromium`` is missing,
so the README's test command (no docs extra) is not affected.
"""

from __future__ import annotations

import functools
import http.server
import importlib.util
import subprocess
import sys
import threading
from dataclasses import dataclass, field
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
#: Where the site is built (the README's command builds the same folder) and where the
#: browser's full-page screenshots go; both git-ignored under docs/_build/.
HTML = ROOT / "docs" / "_build" / "html"
SCREENSHOTS = ROOT / "docs" / "_build" / "screenshots"
CHROMIUM = Path("/usr/bin/chromium")
#: Headless Chromium with nothing that reaches the network on its own.
CHROMIUM_ARGS = ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                 "--disable-background-networking", "--disable-component-update",
                 "--disable-sync"]
#: A site build with the gallery runs every example: generous, never reached in practice.
BUILD_TIMEOUT = 1800.0


def _require(module: str, why: str) -> None:
    if importlib.util.find_spec(module) is None:
        pytest.skip(f"{module} is not installed ({why}; pip install -e \".[docs]\")")


def _tail(text: str, lines: int = 60) -> str:
    return "\n".join(text.strip().splitlines()[-lines:])


@pytest.fixture(scope="session")
def site() -> Path:
    """The HTML site, built once per session with ``python -m sphinx -W -E -b html docs
    docs/_build/html`` in a subprocess (``-E``: every page is read again, so a warning in an
    unchanged page is not hidden by an incremental build); fails with the build's output."""
    _require("sphinx", "the site is built with Sphinx")
    cmd = [sys.executable, "-m", "sphinx", "-W", "-E", "-b", "html", "docs", str(HTML)]
    try:
        proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True,
                              timeout=BUILD_TIMEOUT)
    except subprocess.TimeoutExpired as exc:
        pytest.fail(f"the site's build took over {BUILD_TIMEOUT:.0f} s:\n"
                    f"{_tail(exc.stdout or '')}", pytrace=False)
    if proc.returncode != 0:
        pytest.fail(f"the site's build failed (exit {proc.returncode}): {' '.join(cmd)}\n"
                    f"--- stderr ---\n{_tail(proc.stderr, 200)}\n"
                    f"--- stdout (end) ---\n{_tail(proc.stdout)}", pytrace=False)
    return HTML


class _QuietHandler(http.server.SimpleHTTPRequestHandler):
    def log_message(self, format, *args):  # noqa: A002 (the base class's name)
        pass


@pytest.fixture(scope="session")
def server(site) -> str:
    """The built site served on 127.0.0.1 at a free port (http.server in a thread); its
    root URL, ending in ``/``."""
    httpd = http.server.ThreadingHTTPServer(
        ("127.0.0.1", 0), functools.partial(_QuietHandler, directory=str(site)))
    thread = threading.Thread(target=httpd.serve_forever, name="docs-site", daemon=True)
    thread.start()
    yield f"http://127.0.0.1:{httpd.server_address[1]}/"
    httpd.shutdown()
    httpd.server_close()
    thread.join()


@pytest.fixture(scope="session")
def browser():
    """Debian's headless Chromium, launched through playwright."""
    _require("playwright", "the browser test drives Chromium through playwright")
    if not CHROMIUM.is_file():
        pytest.skip(f"{CHROMIUM} is missing (Debian's chromium package: apt-get install "
                    "chromium)")
    from playwright.sync_api import sync_playwright

    with sync_playwright() as pw:
        chromium = pw.chromium.launch(executable_path=str(CHROMIUM), args=CHROMIUM_ARGS,
                                      headless=True)
        yield chromium
        chromium.close()


def same_site(url: str, root: str) -> bool:
    """True for a URL under the served site's root (scheme, host, port and path)."""
    return url.startswith(root)


@pytest.fixture
def new_context(browser, server):
    """``new_context()``: a fresh browser context (1280 x 900 viewport) in which every
    request outside the served site is aborted, so no page reaches the internet; closed
    after the test."""
    contexts = []

    def new():
        context = browser.new_context(viewport={"width": 1280, "height": 900})
        context.route(lambda url: not same_site(url, server), lambda route: route.abort())
        contexts.append(context)
        return context

    yield new
    for context in contexts:
        context.close()


@dataclass
class Visit:
    """One page opened in the browser: the page itself and what its console reported.

    ``errors`` holds the console's errors and uncaught page errors that come from the site;
    ``external`` the failed loads of resources outside the site (a CDN's script): the test
    machine has no internet and the browser is never let out, so those are reported, not
    failed on.
    """

    page: object
    status: int
    errors: list[str] = field(default_factory=list)
    external: list[str] = field(default_factory=list)


@pytest.fixture
def open_page(new_context, server):
    """``open_page(path)`` opens ``server + path`` in a fresh browser context (requests
    outside the site are aborted) and returns a :class:`Visit`, after the page's load event
    and after every image on it has finished loading or failed."""

    def open_(path: str) -> Visit:
        page = new_context().new_page()
        visit = Visit(page, 0)

        def on_console(msg):
            if msg.type != "error":
                return
            where = (msg.location or {}).get("url", "")
            text = f"{msg.text} ({where})" if where else msg.text
            (visit.errors if not where or same_site(where, server) else
             visit.external).append(text)

        page.on("console", on_console)
        page.on("pageerror", lambda exc: visit.errors.append(f"uncaught: {exc}"))
        response = page.goto(server + path, wait_until="load")
        visit.status = response.status if response is not None else 0
        page.wait_for_function("[...document.images].every(img => img.complete)",
                               timeout=15_000)
        return visit

    return open_


@pytest.fixture(scope="session")
def screenshots() -> Path:
    SCREENSHOTS.mkdir(parents=True, exist_ok=True)
    return SCREENSHOTS
