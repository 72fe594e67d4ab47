#!/usr/bin/env python3
"""Times the demo's drag steps (resolution 6, and the same session at resolution 24) with two
drape binaries side by side, one core each (`taskset -c 0`, `--threads 1`), runs alternating,
and prints the median of every stage's compute time (ms, from `--metrics`) for both.

    python3 scripts/compare_steps.py BEFORE_BINARY [AFTER_BINARY] [--runs N] [--op set]

`--op set` times the demo's dimension edits (`set`) instead of its drags. `--session PATH`
times that session's steps instead of the demo's (for example
assets/sessions/nudges.drape, sixteen small drags at resolution 24).

AFTER_BINARY defaults to target/release/drape. With --log-all, both log the whole recording
(on the same core as the compute, as a one-core user would) and a `logging` row gives the
time of every sink call of the step, and `whole step` the two together. Build the "before" binary from an earlier
commit (`git checkout REV && cargo build --release && cp target/release/drape /tmp/before`).
"""

import argparse
import json
import tempfile
from pathlib import Path

from harness import ROOT, median, run_metrics

GARMENT = ["garment.solve", "constraints.solve", "garment.assemble", "collision.detect", "collision.respond",
           "collision.respond_edges", "collision.quality", "collision.respond_faces",
           "collision.check_faces", "collision.face_clearance"]
M1 = ["m1.select", "m1.subdivide", "m1.collide"]


def drag_timings(binary, session, folder, log_all=False, op="drag"):
    detail = [] if log_all else ["--log-detail", "metrics"]
    steps = run_metrics(binary, folder, "--no-index-cache", "run", session, *detail)
    return [s["timings_ms"] for s in steps if s["op"] == op and "m1.select" in s.get("timings_ms", {})]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("before")
    ap.add_argument("after", nargs="?", default=str(ROOT / "target/release/drape"))
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--log-all", action="store_true", help="log the whole recording, and time it")
    ap.add_argument("--op", default="drag", choices=["drag", "set"], help="the steps to time")
    ap.add_argument("--session", help="time this session's steps instead of the demo's")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        demo = ROOT / "assets/sessions/demo.drape"
        fine = folder / "demo-24.drape"
        fine.write_text(demo.read_text().replace("resolution=6", "resolution=24"))
        sessions = {"resolution 6": demo, "resolution 24": fine}
        if args.session:
            sessions = {Path(args.session).name: Path(args.session).resolve()}
        times = {}
        for _ in range(args.runs):
            for name, session in sessions.items():
                for which, binary in (("before", args.before), ("after", args.after)):
                    for t in drag_timings(binary, session, folder, args.log_all, args.op):
                        for k in GARMENT + M1:
                            times.setdefault((name, which, k), []).append(t.get(k, 0.0))
                        times.setdefault((name, which, "garment"), []).append(sum(t.get(k, 0.0) for k in GARMENT))
                        times.setdefault((name, which, "M1"), []).append(sum(t.get(k, 0.0) for k in M1))
                        times.setdefault((name, which, "compute"), []).append(
                            sum(v for k, v in t.items() if not k.startswith("log.")))
                        times.setdefault((name, which, "logging"), []).append(
                            sum(v for k, v in t.items() if k.startswith("log.")))
                        times.setdefault((name, which, "whole step"), []).append(sum(t.values()))
    for name in sessions:
        print(f"\n{name}: {args.op} steps, one core, median ms over {args.runs} runs of its {args.op}s\n")
        print("| stage | before | after |\n|---|---:|---:|")
        for k in GARMENT + ["garment"] + M1 + ["M1", "compute"] + (["logging", "whole step"] if args.log_all else []):
            a = median(times[(name, "before", k)])
            b = median(times[(name, "after", k)])
            label = f"**{k}**" if k in ("garment", "M1", "compute", "whole step") else k
            print(f"| {label} | {a:.2f} | {b:.2f} |")


if __name__ == "__main__":
    main()
