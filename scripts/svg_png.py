#!/usr/bin/env python3
"""A picture of a pattern SVG (drape's --patterns output is 1:1 in millimetres, far larger
than a screen): the SVG scaled to --height pixels, rendered by Chromium through Playwright
(both from the tools venv that scripts/setup-browser prepares).

    ~/.cache/drape-tools/venv/bin/python scripts/svg_png.py OUT.png PATTERNS.svg [--height 900]
"""
import argparse
import base64
from pathlib import Path

from playwright.sync_api import sync_playwright


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("svg")
    ap.add_argument("--height", type=int, default=900)
    a = ap.parse_args()
    data = base64.b64encode(Path(a.svg).read_bytes()).decode()
    html = (f'<html><body style="margin:0;background:#fff">'
            f'<img id="p" src="data:image/svg+xml;base64,{data}" style="height:{a.height}px"></body></html>')
    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path="/usr/bin/chromium", args=["--no-sandbox"])
        page = browser.new_page(viewport={"width": 2000, "height": a.height})
        page.set_content(html)
        page.wait_for_function("document.getElementById('p').complete")
        page.locator("#p").screenshot(path=a.out)
        browser.close()
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
