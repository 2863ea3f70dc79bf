"""Open every page of the built site in headless Chromium; fail on a console error, a page
error, a failed request or an image that does not load; save screenshots of three pages.

    .venv/bin/python docs/check_site.py [SITE] [--screenshots DIR] [--chromium PATH]

(`make docs-check` builds the site, installs Debian's chromium and the playwright package
when missing, and runs this.) The site is served on 127.0.0.1 at a free port by a thread of
this process; Chromium runs with the flags this machine needs (no sandbox as root, no GPU,
no background networking: nothing leaves the machine). Exit status 0 when every page is
clean, 1 with one line per problem otherwise.
"""

from __future__ import annotations

import argparse
import functools
import http.server
import sys
import threading
from pathlib import Path

CHROMIUM_ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
                 "--no-first-run", "--disable-background-networking",
                 "--disable-component-update", "--disable-sync"]
# the pages photographed: the home page, a tutorial with its figures, a generated reference
SCREENSHOTS = ("index.html", "tutorials/basins.html", "reference/scene-keys.html")

# every <img>: loaded with a size, or (lazy, not yet in view) fetchable
IMAGES_JS = """async () => {
  const bad = [];
  for (const img of document.querySelectorAll('img')) {
    const src = img.currentSrc || img.src;
    if (img.complete && img.naturalWidth > 0) continue;
    try {
      const r = await fetch(src, {method: 'GET'});
      const type = r.headers.get('content-type') || '';
      if (!r.ok || !type.startsWith('image/')) bad.push(src + ' (' + r.status + ')');
    } catch (e) { bad.push(src + ' (' + e + ')'); }
  }
  return bad;
}"""


class _Quiet(http.server.SimpleHTTPRequestHandler):
    def log_message(self, *args):  # the check reports; the server stays silent
        pass


def serve(site: Path) -> tuple[http.server.ThreadingHTTPServer, str]:
    handler = functools.partial(_Quiet, directory=str(site))
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    return server, f"http://127.0.0.1:{server.server_address[1]}/"


def check(site: Path, screenshots: Path | None, chromium: str) -> list[str]:
    """The problems found on every page of ``site`` (empty: all clean)."""
    from playwright.sync_api import sync_playwright

    pages = sorted(p.relative_to(site).as_posix() for p in site.rglob("*.html"))
    if not pages:
        return [f"{site}: no pages (build the site first: make docs)"]
    server, base = serve(site)
    problems: list[str] = []
    try:
        with sync_playwright() as pw:
            browser = pw.chromium.launch(executable_path=chromium, args=CHROMIUM_ARGS)
            page = browser.new_page(viewport={"width": 1280, "height": 900})
            current = {"name": ""}
            page.on("console", lambda m: m.type == "error" and problems.append(
                f"{current['name']}: console error: {m.text}"))
            page.on("pageerror", lambda e: problems.append(f"{current['name']}: {e}"))
            # a request cancelled by leaving the page (lazy images) is no failure; every
            # image is fetched on its own page below
            page.on("requestfailed", lambda r: "ERR_ABORTED" not in (r.failure or "")
                    and problems.append(f"{current['name']}: request failed: {r.url} "
                                        f"({r.failure})"))
            page.on("response", lambda r: r.status >= 400 and problems.append(
                f"{current['name']}: {r.status} for {r.url}"))
            for name in pages:
                current["name"] = name
                response = page.goto(base + name, wait_until="networkidle")
                if response is None or not response.ok:
                    problems.append(f"{name}: not loaded")
                    continue
                problems += [f"{name}: image not loaded: {src}"
                             for src in page.evaluate(IMAGES_JS)]
                if screenshots is not None and name in SCREENSHOTS:
                    screenshots.mkdir(parents=True, exist_ok=True)
                    out = screenshots / (name.replace("/", "_").removesuffix(".html") + ".png")
                    page.screenshot(path=str(out), full_page=False)
                    print(f"screenshot: {out}")
            browser.close()
    finally:
        server.shutdown()
    print(f"{len(pages)} pages loaded, {len(problems)} problems")
    return problems


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("site", nargs="?", default="site", type=Path)
    parser.add_argument("--screenshots", type=Path, default=Path("results/docs-screenshots"))
    parser.add_argument("--chromium", default="/usr/bin/chromium")
    args = parser.parse_args(argv)
    problems = check(args.site, args.screenshots, args.chromium)
    for line in problems:
        print(line, file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
