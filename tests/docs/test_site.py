"""The documentation site, built with warnings as errors and checked in headless Chromium:
its main kinds of page render (a title, every image loaded, no console errors) and no
internal link of the whole site is broken (every same-site URL answers HTTP 200, every
``#fragment`` names an element of its page). Full-page screenshots go to
``docs/_build/screenshots/``.

Run with ``python -m pytest -q -m docs tests/docs`` (after ``pip install -e ".[docs]"``).
"""

from __future__ import annotations

import warnings
from collections import deque
from pathlib import Path
from urllib.parse import unquote

import pytest

pytestmark = pytest.mark.docs


def page_of(site: Path, pattern: str, prefer=lambda html: True) -> str | None:
    """The site-relative path of the first built page matching ``pattern`` (sorted) whose
    HTML satisfies ``prefer``, else the first match, else None."""
    pages = sorted(site.glob(pattern))
    for page in pages:
        if prefer(page.read_text(encoding="utf-8")):
            return page.relative_to(site).as_posix()
    return pages[0].relative_to(site).as_posix() if pages else None


def _has_figure(html: str) -> bool:
    return "sphx-glr-single-img" in html or "sphx-glr-multi-img" in html


def _has_image(html: str) -> bool:
    return "<img " in html


#: The pages opened in the browser, by role: how each is found in the built site (the
#: user guide's first page with an image, else its first page, else the skeleton's bearing
#: page; the flat-head tutorial, else the first tutorial; a gallery example with a figure;
#: the API reference's TapeParameters, else its first generated page).
PAGES = {
    "front-page": lambda site: "index.html",
    "user-guide": lambda site: (page_of(site, "user_guide/**/*.html", prefer=_has_image)
                                or page_of(site, "user-guide/**/*.html", prefer=_has_image)
                                or page_of(site, "bearing.html")),
    "tutorial": lambda site: (page_of(site, "tutorials/flat_head.html")
                              or page_of(site, "tutorials/*.html")),
    "gallery-index": lambda site: page_of(site, "auto_examples/index.html"),
    "gallery-example": lambda site: page_of(site, "auto_examples/**/plot_*.html",
                                            prefer=_has_figure),
    "api-page": lambda site: (page_of(site, "api/generated/gyroshell.TapeParameters.html")
                              or page_of(site, "api/generated/*.html")),
}

#: Every element's id on the page (fragment targets, with the old <a name> anchors) and
#: every same-document reference the browser resolved: links, images, scripts, stylesheets.
_LINKS_AND_IDS = """() => ({
    ids: [...document.querySelectorAll('[id]')].map(e => e.id)
         .concat([...document.querySelectorAll('a[name]')].map(e => e.name)),
    links: [...document.querySelectorAll('a[href]')].map(e => e.href),
    resources: [...document.querySelectorAll('img[src], script[src]')].map(e => e.src)
               .concat([...document.querySelectorAll('link[href]')].map(e => e.href)),
})"""

_IMAGES = """() => [...document.images].map(img => ({
    src: img.currentSrc || img.src, width: img.naturalWidth, height: img.naturalHeight}))"""


def test_the_site_builds_with_warnings_as_errors(site):
    """The README's build command (-W) succeeded and wrote the front page, the three
    generated parts (the gallery, the API reference and the CLI reference), the tutorials,
    the page on which answer to trust and the changelog."""
    for page in ["index.html", "auto_examples/index.html", "api/index.html", "cli.html",
                 "tutorials/index.html", "explanation/trust.html", "changelog.html"]:
        assert (site / page).is_file(), f"{page} was not built"


@pytest.mark.parametrize("role", PAGES)
def test_the_page_renders_in_chromium(role, site, open_page, screenshots):
    """The page loads (HTTP 200), has a document title and a non-empty first heading,
    every <img> on it decoded with a nonzero natural size, and its console reports no
    error and no uncaught exception; a full-page screenshot is saved first."""
    path = PAGES[role](site)
    assert path is not None, f"no {role} page in the built site"
    visit = open_page(path)
    page = visit.page
    page.screenshot(path=str(screenshots / f"{role}.png"), full_page=True)
    problems = [] if visit.status == 200 else [f"HTTP {visit.status}"]
    title = page.title().strip()
    if not title or "<no title>" in title:
        problems.append(f"no document title ({title!r})")
    if not page.locator("h1").first.inner_text().strip():
        problems.append("its first heading is empty")
    images = page.evaluate(_IMAGES)
    problems += [f"image not loaded: {img['src']}" for img in images
                 if not (img["width"] > 0 and img["height"] > 0)]
    problems += [f"console: {error}" for error in visit.errors]
    if role == "gallery-index":
        examples = list((site / "auto_examples").rglob("plot_*.html"))
        if len(images) < len(examples):
            problems.append(f"{len(images)} images for {len(examples)} examples' thumbnails")
    if (role == "gallery-example" and _has_figure((site / path).read_text(encoding="utf-8"))
            and not any("/_images/sphx_glr_" in img["src"] for img in images)):
        problems.append("its figure is not among the page's images")
    assert not problems, f"{path} in Chromium:\n" + "\n".join(problems)
    if visit.external:
        warnings.warn(f"{path}: resources outside the site, not loaded here (the browser is "
                      f"kept offline): {visit.external}", stacklevel=1)


def _status(context, page, url: str) -> tuple[int, bool]:
    """HTTP status of ``url`` and whether it is an HTML page, which is then open in ``page``
    (a page's URL is opened at once; any other URL gets a HEAD request first)."""
    if not url.endswith((".html", "/")):
        head = context.request.fetch(url, method="HEAD")
        if head.status != 200 or "text/html" not in head.headers.get("content-type", ""):
            return head.status, False
    response = page.goto(url, wait_until="domcontentloaded")
    status = response.status if response is not None else 0
    return status, "text/html" in (response.headers.get("content-type", "") if response else "")


def crawl(context, root: str) -> tuple[list[str], int]:
    """Visit every same-site URL reachable from ``root``: each answers HTTP 200; each HTML
    page is opened in the browser and yields its links, resources and ids. Returns the
    broken references (with the page that refers to each) and the number of URLs checked."""
    page = context.new_page()
    referrer = {root: "(start)"}
    queue, ids, fragments, broken = deque([root]), {}, [], []
    while queue:
        url = queue.popleft()
        status, html = _status(context, page, url)
        if status != 200:
            broken.append(f"{url}: HTTP {status} (linked from {referrer[url]})")
            continue
        if not html:
            continue
        found = page.evaluate(_LINKS_AND_IDS)
        ids[url] = set(found["ids"])
        for href in found["links"] + found["resources"]:
            if not href.startswith(root):
                continue
            target, _, fragment = href.partition("#")
            if fragment:
                fragments.append((url, target, unquote(fragment)))
            if target not in referrer:
                referrer[target] = url
                queue.append(target)
    for source, target, fragment in fragments:
        if target in ids and fragment not in ids[target]:
            broken.append(f"{target}#{fragment}: no element with that id (linked from "
                          f"{source})")
    return broken, len(referrer)


def test_no_internal_link_is_broken(site, server, new_context):
    """Every link, image, script and stylesheet of the site that points inside it, followed
    from the front page, answers HTTP 200, and every #fragment exists on its page."""
    broken, checked = crawl(new_context(), server)
    assert checked > len(list(site.glob("*.html"))), f"the crawl reached only {checked} URLs"
    assert not broken, f"{len(broken)} broken of {checked} internal URLs:\n" + "\n".join(
        sorted(set(broken)))


#: Escapes that must never reach a reader: HTML entities shown as text (an index entry
#: escaped twice) and the reStructuredText escapes of the CLI reference's help texts.
_ESCAPES = ("&#x27;", "&amp;", "&quot;", "&lt;", "&gt;", "\\_", "\\*")


@pytest.mark.parametrize("query", ["critical", "Benson", "reproduce"])
def test_search_results_read_as_plain_text(query, site, open_page, screenshots):
    """The site's search page finds the query, and no result's title or summary shows an
    escape (``&#x27;`` for an apostrophe was the symptom: the CLI's commands entered the
    index under their HTML-escaped descriptions, which the search page escaped again)."""
    visit = open_page(f"search.html?q={query}")
    page = visit.page
    page.wait_for_function(
        "() => document.querySelectorAll('#search-results li').length > 0"
        " || /found 0|did not match/i.test(document.body.innerText)", timeout=30_000)
    page.screenshot(path=str(screenshots / f"search-{query}.png"), full_page=True)
    results = page.locator("#search-results li").all_inner_texts()
    assert results, f"searching {query!r} found nothing"
    shown = [text for text in results if any(escape in text for escape in _ESCAPES)]
    assert not shown, f"search results for {query!r} show escapes: {shown[:5]}"
    if query == "critical":
        assert any(text.startswith("gyroshell critical") for text in results), results[:10]
    assert not visit.errors, visit.errors
