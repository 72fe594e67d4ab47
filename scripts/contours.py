#!/usr/bin/env python3
"""Time against error of the contour curves: the demo's drags with `contours=local` (the
default, cubic spans with local support) and `contours=natural` (the C2 spline, every span on
every point), run side by side by one binary on one core (`taskset -c 0`, `--threads 1`), runs
alternating. Prints, at resolutions 6 and 24:

- the median drag step (the garment stages, ms, from `--metrics`) and the patches re-surfaced;
- how far M0 moves from one kind to the other (every step's M0 from `--export`, vertex by
  vertex, mm), on every body in assets/bodies and the built-in one (resolution 6);
- how many M0 vertices each drag moves (more than 0.1 mm) with each kind;
- the quality after every step with each kind (vertices inside, crossing edges), which must
  be 0 and 0.

    python3 scripts/contours.py [--runs N] [--binary target/release/drape] [--readme]

With --readme, also writes what it printed into README.md between `<!-- figures:contours -->`
and `<!-- /figures:contours -->`.
"""

import argparse
import json
import io
import math
import statistics
import tempfile
from contextlib import redirect_stdout
from pathlib import Path

from harness import ROOT, run_metrics, splice

GARMENT = ["constraints.solve", "garment.assemble", "collision.detect", "collision.respond",
           "collision.respond_edges", "collision.quality"]
KINDS = ["local", "natural"]


def session(kind, resolution):
    text = (ROOT / "assets/sessions/demo.drape").read_text()
    return text.replace("fit=tight resolution=6", f"fit=tight contours={kind} resolution={resolution}")


def run(binary, text, folder, extra=(), export=None):
    path = folder / "s.drape"
    path.write_text(text)
    more = ["--export", export] if export else []
    return run_metrics(binary, folder, "run", path, *extra, "--log-detail", "metrics", *more)


def vertices(path):
    return [tuple(map(float, line.split()[1:4])) for line in path.read_text().splitlines()
            if line.startswith("v ")]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--binary", default=str(ROOT / "target/release/drape"))
    ap.add_argument("--readme", action="store_true", help="write the report into its page (figures:contours, in docs/)")
    args = ap.parse_args()
    out = io.StringIO()
    with redirect_stdout(out):
        report(args)
    text = out.getvalue()
    print(text, end="")
    if args.readme:
        splice(None, "contours", text)


def report(args):
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        print(f"#### Drag steps, one core, median over {args.runs} runs of the demo's 4 drags\n")
        print("| resolution | contours | garment ms | assemble ms | patches re-surfaced (median) |")
        print("|---:|---|---:|---:|---:|")
        for res in (6, 24):
            times = {k: ([], [], []) for k in KINDS}
            for _ in range(args.runs):
                for kind in KINDS:
                    for s in run(args.binary, session(kind, res), folder):
                        if s["op"] != "drag" or "m1.select" not in s.get("timings_ms", {}):
                            continue
                        t = s["timings_ms"]
                        times[kind][0].append(sum(t.get(k, 0.0) for k in GARMENT))
                        times[kind][1].append(t.get("garment.assemble", 0.0))
                        times[kind][2].append(s["resurfaced_patches"])
            for kind in KINDS:
                g, a, r = times[kind]
                print(f"| {res} | {kind} | {statistics.median(g):.1f} | {statistics.median(a):.1f} | "
                      f"{statistics.median(r):.0f} |")
        print("\n#### M0, local against natural contours (resolution 6, every step's M0)\n")
        print("| body | largest move, mm | mean move, mm | M0 vertices moved by the 4 drags, "
              "natural -> local | inside / crossing after every step, local (natural) |")
        print("|---|---:|---:|---|---|")
        bodies = sorted((ROOT / "assets/bodies").glob("*.obj"))
        for body in [None, *bodies]:
            extra = ("--body", str(body)) if body else ()
            meshes, quality = {}, {}
            for kind in KINDS:
                out = folder / f"export-{kind}"
                if out.exists():
                    for f in out.iterdir():
                        f.unlink()
                steps = run(args.binary, session(kind, 6), folder, extra, export=out)
                meshes[kind] = {f.name: vertices(f) for f in sorted(out.glob("step*_m0.obj"))}
                quality[kind] = (max(s.get("penetrating_vertices", 0) for s in steps),
                                 max(s.get("crossing_edges", 0) for s in steps))
            names = sorted(meshes["local"])
            moves = [math.dist(a, b) for n in names
                     for a, b in zip(meshes["natural"][n], meshes["local"][n])]
            drags = []
            for kind in ["natural", "local"]:
                counts = []
                for before, after in zip(names, names[1:]):
                    if after[:6] in ("step07", "step08", "step09", "step10"):
                        counts.append(sum(math.dist(a, b) > 1e-4 for a, b in
                                          zip(meshes[kind][before], meshes[kind][after])))
                drags.append("/".join(map(str, counts)))
            name = body.stem if body else "builtin"
            q = f"{quality['local'][0]} / {quality['local'][1]} ({quality['natural'][0]} / {quality['natural'][1]})"
            print(f"| {name} | {1000 * max(moves):.1f} | {1000 * statistics.mean(moves):.2f} | "
                  f"{drags[0]} -> {drags[1]} of {len(meshes['local'][names[0]])} | {q} |")


if __name__ == "__main__":
    main()
