#!/usr/bin/env python3
"""Opens a drape `--serve-web` URL in headless Chromium and checks the picture shows the scene.

  python scripts/web_check.py URL OUT.png [--timeout 240]

Needs Debian's Chromium (/usr/bin/chromium) and Playwright (`pip install playwright`; its
own browser download is not used). `scripts/setup-browser` installs both. The page is Rerun's
web viewer served by drape; it loads the data from drape's gRPC server. Every few seconds a
1280x800 screenshot is taken; the check passes when the 3D views hold the garment and the
body: strongly coloured pixels (saturation >= 0.45, value >= 0.35: the garment's patch
colours, the partition tints), where the viewer's own chrome and background are grey or
pastel. Once found, it waits (at most a minute) for two equal screenshots in a row, so the
picture saved shows the end of the session. It prints one JSON line with the fractions
found and exits 0 when found, 1 if the picture never came (the last screenshot is saved
either way).
"""
from __future__ import annotations

import argparse
import colorsys
import json
import sys
import time

from PIL import Image
from playwright.sync_api import sync_playwright

# The default blueprint at 1280x800: the main 3D view (top left) and the M1 view (bottom
# left), in pixels (left, top, right, bottom).
REGIONS = {"scene": (0, 60, 950, 470), "m1": (0, 500, 310, 770)}
# A region shows its subject when at least this fraction of its pixels is strongly coloured.
MIN_FRACTION = 0.02
CHROMIUM_ARGS = [
    "--no-sandbox",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--use-angle=swiftshader",
    "--enable-unsafe-swiftshader",
    "--ignore-gpu-blocklist",
]


def coloured_fraction(img: Image.Image, box: tuple[int, int, int, int]) -> float:
    """Fraction of pixels in `box` with saturation >= 0.45 and value >= 0.35 (sampled every 2 px)."""
    region = img.convert("RGB").crop(box)
    w, h = region.size
    px = region.load()
    hits = total = 0
    for y in range(0, h, 2):
        for x in range(0, w, 2):
            r, g, b = px[x, y]
            _, s, v = colorsys.rgb_to_hsv(r / 255, g / 255, b / 255)
            total += 1
            hits += s >= 0.45 and v >= 0.35
    return hits / max(total, 1)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("url")
    ap.add_argument("out")
    ap.add_argument("--timeout", type=float, default=240.0, help="seconds to wait for the scene")
    args = ap.parse_args()
    start = time.monotonic()
    fractions: dict[str, float] = {}
    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path="/usr/bin/chromium", headless=True, args=CHROMIUM_ARGS)
        page = browser.new_page(viewport={"width": 1280, "height": 800})
        page.goto(args.url)
        shown = False
        while time.monotonic() - start < args.timeout:
            time.sleep(3)
            page.screenshot(path=args.out)
            img = Image.open(args.out)
            fractions = {name: round(coloured_fraction(img, box), 4) for name, box in REGIONS.items()}
            if all(f >= MIN_FRACTION for f in fractions.values()):
                shown = True
                break
        # The viewer follows the stream as it arrives: wait (at most a minute) until two
        # screenshots in a row agree, so the picture saved shows the whole session.
        previous = None
        settle_until = time.monotonic() + 60
        while shown and time.monotonic() < settle_until:
            current = page.screenshot(path=args.out)
            if current == previous:
                break
            previous = current
            time.sleep(3)
        browser.close()
    print(json.dumps({"shown": shown, "seconds": round(time.monotonic() - start, 1), "coloured": fractions}))
    return 0 if shown else 1


if __name__ == "__main__":
    sys.exit(main())
