#!/usr/bin/env python3
"""The whole edit step a user waits for, per resolution and per stage: the demo session at
resolutions 3, 6, 12 and 24, on one core (`taskset -c 0`, `--threads 1`) and on every core
(`--threads N`), the median over `--runs` runs of its drag steps and of its `set` steps; each
stage's compute time and the logging (every stage written to the recording file and settled,
as a user's file gets it), all from `--metrics`.

    python3 scripts/step_table.py [--runs N] [--binary PATH] [--write]

`--write` puts the table into docs/performance.md (section `figures:steps`). Builds nothing:
run `cargo build --release` first (the default binary is target/release/drape).
"""

import os
import tempfile
from pathlib import Path

from harness import ROOT, median, run_metrics, runs_and_binary, splice

RESOLUTIONS = [3, 6, 12, 24]
# Columns: a name and the timing keys (prefixes) it sums.
STAGES = [
    ("solve", ["constraints.", "garment.solve"]),
    ("assemble", ["garment.assemble"]),
    ("M0 collision", ["collision."]),
    ("M1 select", ["m1.select"]),
    ("M1 subdivide", ["m1.subdivide"]),
    ("M1 collide", ["m1.collide"]),
]


def stage_ms(timings, prefixes):
    return sum(v for k, v in timings.items() if any(k.startswith(p) for p in prefixes))


def step_rows(steps, op):
    """Per step of kind `op` that made an M1: each column's ms, the rest of the compute, the
    logging, the whole step and the M1 patches kept."""
    rows = []
    for s in steps:
        t = s.get("timings_ms", {})
        if s["op"] != op or "m1.select" not in t:
            continue
        compute = {k: v for k, v in t.items() if not k.startswith("log.")}
        row = {name: stage_ms(compute, prefixes) for name, prefixes in STAGES}
        row["other compute"] = max(0.0, sum(compute.values()) - sum(row.values()))  # not -0.0 from rounding
        row["compute"] = sum(compute.values())
        row["logging"] = sum(v for k, v in t.items() if k.startswith("log."))
        row["whole step"] = row["compute"] + row["logging"]
        row["M1 patches kept"] = s.get("work", {}).get("m1.patches_kept", 0)
        rows.append(row)
    return rows


def main():
    ap = runs_and_binary()
    ap.add_argument("--write", action="store_true", help="write the table into docs/performance.md")
    args = ap.parse_args()
    cores = os.cpu_count() or 1
    demo = (ROOT / "assets/sessions/demo.drape").read_text()
    columns = [name for name, _ in STAGES] + ["other compute", "compute", "logging", "whole step", "M1 patches kept"]
    table = {}
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        for run in range(args.runs):
            for r in RESOLUTIONS:
                session = folder / f"demo-{r}.drape"
                session.write_text(demo.replace("resolution=6", f"resolution={r}"))
                for threads in sorted({1, cores}):
                    steps = run_metrics(args.binary, folder, "--no-index-cache", "run", session, threads=threads)
                    for op in ("drag", "set"):
                        for row in step_rows(steps, op):
                            for c in columns:
                                table.setdefault((r, op, threads, c), []).append(row[c])
            print(f"run {run + 1} of {args.runs} done", flush=True)
    lines = [
        f"#### The whole step, per stage (the demo's drags and `set`s, median ms over {args.runs} runs; "
        f"`python3 scripts/step_table.py --runs {args.runs} --write`)",
        "",
        "| resolution | step | threads | " + " | ".join(columns) + " |",
        "|---:|---|---:|" + "---:|" * len(columns),
    ]
    for r in RESOLUTIONS:
        for op in ("drag", "set"):
            for threads in sorted({1, cores}):
                cells = []
                for c in columns:
                    v = median(table.get((r, op, threads, c), []))
                    cells.append(f"{v:.0f}" if c == "M1 patches kept" else f"{v:.1f}")
                lines.append(f"| {r} | {op} | {threads} | " + " | ".join(cells) + " |")
    body = "\n".join(lines)
    print(body)
    if args.write:
        splice(ROOT / "docs/performance.md", "steps", body)


if __name__ == "__main__":
    main()
