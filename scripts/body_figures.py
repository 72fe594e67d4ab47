#!/usr/bin/env python3
"""Per-body collision figures of a session on every body in assets/bodies/.

    python3 scripts/body_figures.py [--session assets/sessions/demo.drape] [--drape BIN] [--summary]

Runs `drape run SESSION --body B --verify --metrics` for each body and prints, per body and
per step with a collision: hits (with the brute-force truth), moves by rule, crossing edges
before the response -> per edge round -> after, vertices inside after, the farthest a vertex
was moved and the largest stretch of an edge ('-' from a binary that does not report them),
and the step's compute time (ms, not logging). Standard library only.
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


def mm(v):
    """Metres as millimetres; '-' where the binary does not report it."""
    return "-" if v is None else f"{v * 1e3:.1f}"


def ratio(v):
    return "-" if v is None else f"{v:.2f}"


def bodies():
    return sorted(glob.glob(os.path.join(ROOT, "assets", "bodies", "*.obj")))


def arms_table(drape):
    """One row per body: its arms' figures from the scene (the left arm; the right mirrors
    it), in metres and degrees."""
    rows = [
        "| body | arm, shoulder to wrist | upper arm | bend at the elbow | girth across at the elbow "
        "| at the wrist | elbow height | wrist height |",
        "|---|---:|---:|---:|---:|---:|---:|---:|",
    ]
    with tempfile.TemporaryDirectory() as tmp:
        session = os.path.join(tmp, "scene.drape")
        with open(session, "w") as f:
            f.write("drape 1\nbody builtin\n")
        for body in bodies():
            scene = run(drape, session, body, tmp)[0]
            arm = next((a for a in scene.get("arms", []) if a["side"] == "left"), None)
            if arm is None:
                rows.append(f"| {os.path.basename(body)[:-4]} | no arm found | | | | | | |")
                continue
            height = {(l["kind"], l["side"]): l["point"][1] for l in scene["landmarks"]}
            girth = lambda v: "-" if v is None else f"{v:.3f} m"
            rows.append(
                f"| {os.path.basename(body)[:-4]} | {arm['length_m']:.3f} m | {arm['upper_m']:.3f} m "
                f"| {arm['bend_deg']:.0f} deg | {girth(arm['elbow_girth'])} | {girth(arm['wrist_girth'])} "
                f"| {height[('elbow', 'left')]:.3f} m | {height[('wrist', 'left')]:.3f} m |")
    return "\n".join(rows)


def summary(drape, session):
    """One row per body: the session's collision steps in a line (no timings, so the rows
    are the same run to run)."""
    rows = [
        "| body | steps | crossing edges before response, most | edge rounds, most "
        "| inside / crossing after, every step (`--verify`) | farthest move mm | largest edge stretch |",
        "|---|---:|---:|---:|---|---:|---:|",
    ]
    with tempfile.TemporaryDirectory() as tmp:
        for body in bodies():
            steps = [s for s in run(drape, session, body, tmp) if "hits" in s]
            after = {(s["verify"]["inside_after"], s["verify"]["crossing_after"]) for s in steps}
            after = ", ".join(f"{i} / {c}" for i, c in sorted(after))
            rows.append(
                f"| {os.path.basename(body)[:-4]} | {len(steps)} "
                f"| {max(s['verify']['crossing_before'] for s in steps)} "
                f"| {max(len(s['crossing_edges_by_round']) for s in steps)} | {after} "
                f"| {mm(max(s.get('max_move_m', 0) for s in steps))} "
                f"| {ratio(max(s.get('max_stretch', 1) for s in steps))} |")
    return "\n".join(rows)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--session", default="assets/sessions/demo.drape")
    ap.add_argument("--drape", default=os.path.join(ROOT, "target", "release", "drape"))
    ap.add_argument("--summary", action="store_true", help="one row per body (the README's table)")
    args = ap.parse_args()
    if args.summary:
        print(summary(args.drape, args.session))
        return 0
    with tempfile.TemporaryDirectory() as tmp:
        for body in bodies():
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
                      f"| {s['penetrating_vertices']} | {mm(s.get('max_move_m'))} | {ratio(s.get('max_stretch'))} | {ms:.1f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
