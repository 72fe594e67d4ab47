#!/usr/bin/env python3
"""Per-body collision figures of a session on every body in assets/bodies/.

    python3 scripts/body_figures.py [--session assets/sessions/demo.drape] [--drape BIN]

Runs `drape run SESSION --body B --verify --metrics` for each body and prints, per body and
per step with a collision: hits (with the brute-force truth), moves by rule, crossing edges
before the response -> per edge round -> after, vertices inside after, the farthest a vertex
was moved and the largest stretch of an edge, and the step's compute time (ms, not logging). Standard library only.
"""
import argparse
import glob
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def run(drape, session, body, tmp):
    metrics = os.path.join(tmp, os.path.basename(body) + ".json")
    subprocess.run([drape, "run", session, "--body", body, "--verify", "--metrics", metrics,
                    "--save", os.path.join(tmp, "x.rrd")], cwd=ROOT, check=False,
                   stderr=subprocess.DEVNULL)
    with open(metrics) as f:
        return json.load(f)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--session", default="assets/sessions/demo.drape")
    ap.add_argument("--drape", default=os.path.join(ROOT, "target", "release", "drape"))
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        for body in sorted(glob.glob(os.path.join(ROOT, "assets", "bodies", "*.obj"))):
            steps = run(args.drape, args.session, body, tmp)
            print(f"\n{os.path.basename(body)}\n")
            print("| step | hits (truth) | moves by rule | crossing before -> rounds -> after | inside after | farthest move mm | edge stretch | compute ms |")
            print("|---|---|---|---|---|---:|---:|---:|")
            for s in steps:
                if "hits" not in s:
                    continue
                v = s.get("verify", {})
                rules = ", ".join(f"{k} {n}" for k, n in s["responses_by_rule"].items()) or "-"
                rounds = ", ".join(str(r) for r in s["crossing_edges_by_round"])
                ms = sum(t for k, t in s["timings_ms"].items() if not k.startswith("log.") and k != "collision.verify")
                print(f"| {s['step']} {s['op']} | {s['hits']} ({v.get('inside_before', '?')}) | {rules} "
                      f"| {v.get('crossing_before', '?')} -> {rounds} -> {s['crossing_edges']} "
                      f"| {s['penetrating_vertices']} | {s.get('max_move_m', 0) * 1e3:.1f} | {s.get('max_stretch', 1):.2f} | {ms:.1f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
