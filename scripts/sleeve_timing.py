#!/usr/bin/env python3
"""Times a step on a garment with sleeves and a collar next to the same step on the sleeveless
jumpsuit: the same session (a dimension edit, a drag of a torso point, then the ease down)
with `garment jumpsuit`, `garment jumpsuit sleeves=long collar=stand` and `garment shirt`,
at resolution 6 and 24, one core each (`taskset -c 0`, `--threads 1`), runs alternating;
prints the median compute and logging time of each step kind (ms, from `--metrics`: the
whole step a user waits for, M1 and the certificate included) and the garment's size.

    python3 scripts/sleeve_timing.py [--binary target/release/drape] [--runs 3] [--write]

With --write the table goes into the page that holds `figures:sleeve-timing`.
"""

import argparse
import tempfile
from pathlib import Path

from harness import ROOT, median, run_metrics, splice

SESSION = """drape 1
body builtin
units m
m1
garment {garment} resolution={resolution}
set waist_girth +0.02
drag waist.front_left by=0,0,0.02
set ease 0.006
"""

GARMENTS = ["jumpsuit", "jumpsuit sleeves=long collar=stand", "shirt"]


def step_times(binary, folder, garment, resolution):
    """Per step of the session: (op, compute ms, logging ms, M0 vertices)."""
    session = Path(folder) / "timing.drape"
    session.write_text(SESSION.format(garment=garment, resolution=resolution))
    out = []
    vertices = 0
    for s in run_metrics(binary, folder, "--no-index-cache", "run", session):
        if s["op"] in ("scene",):
            continue
        t = s.get("timings_ms", {})
        log = sum(v for k, v in t.items() if k.startswith("log."))
        compute = sum(v for k, v in t.items() if not k.startswith("log.") and k != "body.index")
        # A drag keeps the garment's size: carry the last count on.
        vertices = s.get("m0_vertices") or vertices
        out.append((s["op"], compute, log, vertices))
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--binary", default=str(ROOT / "target/release/drape"))
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--write", action="store_true")
    args = ap.parse_args()
    rows = {}
    with tempfile.TemporaryDirectory() as tmp:
        for _ in range(args.runs):
            for resolution in (6, 24):
                for garment in GARMENTS:
                    for k, (op, compute, log, verts) in enumerate(step_times(args.binary, tmp, garment, resolution)):
                        key = (resolution, k, op)
                        rows.setdefault(key, {}).setdefault(garment, []).append((compute, log, verts))
    lines = ["| resolution | step | " + " | ".join(f"`{g}`: compute + logging" for g in GARMENTS) + " |",
             "|---|---|" + "---:|" * len(GARMENTS)]
    for (resolution, _, op), by in sorted(rows.items()):
        cells = []
        for g in GARMENTS:
            runs = by.get(g, [])
            c, l = median([r[0] for r in runs]), median([r[1] for r in runs])
            v = runs[0][2] if runs else 0
            cells.append(f"{c:.1f} + {l:.1f} ms ({v} vertices)")
        lines.append(f"| {resolution} | {op} | " + " | ".join(cells) + " |")
    table = "\n".join(lines)
    print(table)
    if args.write:
        splice(None, "sleeve-timing", table)


if __name__ == "__main__":
    main()
