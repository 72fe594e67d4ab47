#!/usr/bin/env python3
"""Figures of the face certificate (docs/faces.md), from runs a reader can repeat.

    python3 scripts/faces.py [--binary target/release/drape]
        The demo with --verify on the built-in body and on every body of assets/bodies:
        per collided step, the faces pierced before the face rounds and after them (the
        step's own check), the brute-force truth after (every body edge against every
        face), the same for M1, and the face and vertex clearance (mm).

    python3 scripts/faces.py --refusals BEFORE_BINARY [--sessions N]
        `drape stress --bodies assets/bodies --sessions N --json` with both binaries (the
        same sessions): the refusals by reason side by side, with the steps accepted and the
        solves reported not converged.

    python3 scripts/faces.py --sweep REPORT.json... [--doc-sweep]
        The verified sweep, from the --report files of its shards (`drape stress --bodies
        assets/bodies --sessions 100 --verify --threads 1 --shard I/N --report sI.json`),
        merged: per body the collisions checked against the brute-force truth (faces
        included) and against a full check; with --doc-sweep written into docs/faces.md.

    python3 scripts/faces.py --doc BEFORE_BINARY [--only faces-refusals,...]
        All three (the third: scripts/compare_steps.py BEFORE_BINARY --runs 3), or those named,
        written into docs/faces.md between its `<!-- figures:faces-* -->` markers.
"""

import argparse
import contextlib
import io
import json
import subprocess
import tempfile
from pathlib import Path

from harness import ROOT, splice

BODIES = ["builtin"] + sorted(p.name for p in (ROOT / "assets/bodies").glob("*.obj"))


def demo(binary, body, folder):
    metrics = folder / "metrics.json"
    extra = [] if body == "builtin" else ["--body", str(ROOT / "assets/bodies" / body)]
    subprocess.run([str(binary), "run", "--verify", *extra, "--metrics", str(metrics),
                    "--save", str(folder / "run.rrd")], cwd=ROOT, capture_output=True, check=True)
    return json.loads(metrics.read_text())


def faces_table(binary):
    print("| body | step | edit | pierced before rounds -> after | truth after | M1 before -> after | "
          "M1 truth | face clearance mm | vertex clearance mm |")
    print("|---|---:|---|---|---:|---|---:|---:|---:|")
    with tempfile.TemporaryDirectory() as tmp:
        for body in BODIES:
            for s in demo(binary, body, Path(tmp)):
                if "pierced_faces" not in s:
                    continue
                rounds = s["pierced_faces_by_round"]
                m1 = s.get("m1_pierced_faces_before"), s.get("m1_pierced_faces")
                print(f"| {body} | {s['step']} | {s['op']} | {rounds[0]} -> {s['pierced_faces']} | "
                      f"{s['verify']['pierced_after']} | {m1[0]} -> {m1[1]} | "
                      f"{(s.get('m1_verify') or {}).get('pierced', '-')} | "
                      f"{s['face_clearance_m'] * 1e3:.3f} | {s['vertex_clearance_m'] * 1e3:.3f} |")


def stress(binary, sessions):
    out = subprocess.run([str(binary), "stress", "--bodies", str(ROOT / "assets/bodies"), "--sessions",
                          str(sessions), "--json", "--out", tempfile.mkdtemp()],
                         cwd=ROOT, capture_output=True, text=True)
    return json.loads(out.stdout)["overall"]


def refusals(before, after, sessions):
    old, new = stress(before, sessions), stress(after, sessions)
    print(f"`drape stress --bodies assets/bodies --sessions {sessions}`: {old['sessions']} sessions, "
          f"{old['steps']} steps\n")
    print("| | before | after |\n|---|---:|---:|")
    print(f"| steps accepted | {old['accepted']} | {new['accepted']} |")
    print(f"| solves reported not converged | {old['solves_not_converged']} | {new['solves_not_converged']} |")
    print(f"| largest residual of a converged solve | {old['max_residual_converged']:.2e} | "
          f"{new['max_residual_converged']:.2e} |")
    print(f"| guarantee failures, panics | {old['guarantee_failures']}, {old['panics']} | "
          f"{new['guarantee_failures']}, {new['panics']} |")
    print("\n| refused: reason | before | after |\n|---|---:|---:|")
    reasons = sorted(set(old["refused"]) | set(new["refused"]),
                     key=lambda r: (-(old["refused"].get(r, 0) + new["refused"].get(r, 0)), r))
    for r in reasons:
        print(f"| {r} | {old['refused'].get(r, 0)} | {new['refused'].get(r, 0)} |")


def sweep(binary, reports):
    from readme_figures import verified_table
    merged = json.loads(subprocess.run([str(binary), "stress", "merge", "--json", *reports], cwd=ROOT,
                                       check=True, capture_output=True, text=True).stdout)
    report = merged["report"] if "report" in merged else merged
    title = (f"`drape stress --bodies assets/bodies --sessions {report['sessions_per_body']} "
             f"--steps {report['steps_per_session']} --verify --threads 1`, {len(reports)} shard(s) merged "
             f"(`stress merge`), seed {report['seed']}:")
    o = merged["overall"]
    print(verified_table(merged, title))
    print(f"\nSteps accepted {o['accepted']} of {o['steps']}; guarantee failures {o['guarantee_failures']}; "
          f"panics {o['panics']}; non-finite outputs {o['non_finite']}.")


def captured(f, *a):
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        f(*a)
    return out.getvalue().strip()


def write_doc(before, after, sessions, only):
    makers = {
        "faces-demo": lambda: captured(faces_table, after),
        "faces-refusals": lambda: captured(refusals, before, after, sessions),
        "faces-steps": lambda: subprocess.run(
            ["python3", str(ROOT / "scripts/compare_steps.py"), before, after, "--runs", "3"],
            cwd=ROOT, capture_output=True, text=True, check=True).stdout.strip(),
    }
    sections = {name: make() for name, make in makers.items() if not only or name in only}
    for name, body in sections.items():
        splice(ROOT / "docs/faces.md", name, body)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--binary", default=str(ROOT / "target/release/drape"))
    ap.add_argument("--refusals", metavar="BEFORE_BINARY")
    ap.add_argument("--sessions", type=int, default=100)
    ap.add_argument("--doc", metavar="BEFORE_BINARY")
    ap.add_argument("--only", default="", help="with --doc: the sections to write, comma-separated "
                    "(faces-demo, faces-refusals, faces-steps); all by default")
    ap.add_argument("--sweep", nargs="+", metavar="REPORT")
    ap.add_argument("--doc-sweep", action="store_true", help="with --sweep: write it into docs/faces.md")
    args = ap.parse_args()
    if args.sweep:
        body = captured(sweep, args.binary, args.sweep)
        print(body)
        if args.doc_sweep:
            splice(ROOT / "docs/faces.md", "faces-sweep", body)
    elif args.doc:
        write_doc(args.doc, args.binary, args.sessions, [s for s in args.only.split(",") if s])
    elif args.refusals:
        refusals(args.refusals, args.binary, args.sessions)
    else:
        faces_table(args.binary)


if __name__ == "__main__":
    main()
