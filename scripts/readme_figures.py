#!/usr/bin/env python3
"""Regenerates the generated figures of the README and docs/ from `drape run --verify --metrics`.

    python3 scripts/readme_figures.py            # run the demo, rewrite the generated sections
    python3 scripts/readme_figures.py --check    # exit 1 if a page is out of date
    python3 scripts/readme_figures.py --metrics M.json   # use an existing metrics file
    python3 scripts/readme_figures.py --bench    # also the M1 benchmark, logging and NURBS
                                                 # experiment tables (times vary)
    python3 scripts/readme_figures.py --stress   # also the verified stress sweep (about 20
                                                 # minutes on 2 cores; its times vary)

Each generated section sits between `<!-- figures:NAME -->` and `<!-- /figures:NAME -->`
in README.md or a page under docs/; nothing else is touched. Standard library only.
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile

from harness import ROOT as ROOT_PATH, doc_files, splice_text

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SESSION = os.path.join(ROOT, "assets", "sessions", "demo.drape")
SCENE = {"drape", "body", "units", "landmark", "solver", "m1"}

# The drape binary the figures come from (--binary); by default `cargo run --release`.
BINARY = None


def built():
    """The path of the drape binary: the one given with --binary, else target/release/drape
    (built first)."""
    if BINARY:
        return BINARY
    subprocess.run(["cargo", "build", "--release", "--quiet"], cwd=ROOT, check=True)
    return os.path.join(ROOT, "target", "release", "drape")


def drape():
    """The command that runs drape: the binary given with --binary, else `cargo run`."""
    return [BINARY] if BINARY else ["cargo", "run", "--release", "--quiet", "--"]


def demo_metrics():
    """Runs the demo with --verify; returns its metrics."""
    with tempfile.TemporaryDirectory() as tmp:
        metrics = os.path.join(tmp, "demo.json")
        subprocess.run(
            [*drape(), "run", "--verify",
             "--metrics", metrics, "--save", os.path.join(tmp, "demo.rrd")],
            cwd=ROOT, check=True, stderr=subprocess.DEVNULL)
        with open(metrics) as f:
            return json.load(f)


def step_texts():
    """The demo's steps as written, by step number (1-based)."""
    out = {}
    n = 0
    for line in open(SESSION):
        text = line.split("#", 1)[0].strip()
        if not text or text.split()[0] in SCENE:
            continue
        n += 1
        out[n] = text
    return out


def collision_table(steps, texts):
    rows = [
        "| step | tested / inert / patch-skipped | hits (truth) | missed / false | moved (vertex + edge + face rounds) "
        "| crossing edges before -> per round -> after | pierced faces per round -> after (truth) | inside after "
        "| face / vertex clearance mm |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for s in steps:
        if "hits" not in s:
            continue
        v = s.get("verify", {})
        missed, false = v.get("missed", "?"), v.get("false_hits", "?")
        note = ""
        if (missed or false) and missed == v.get("missed_by", {}).get("line_line") and false == v.get("false_line_line"):
            note = ", all line-line"
        rounds = ", ".join(str(r) for r in s["crossing_edges_by_round"])
        rows.append(
            f"| {s['step']} `{texts.get(s['step'], s['op'])}` "
            f"| {s['tested_vertices']} / {s['skipped_inert']} / {s['skipped_patch']} "
            f"| {s['hits']} ({v.get('inside_before', '?')}) | {missed} / {false}{note} "
            f"| {s['responses']} + {s['edge_responses']} + {s['face_responses']} "
            f"| {v.get('crossing_before', '?')} -> {rounds} -> {s['crossing_edges']} "
            f"| {', '.join(str(r) for r in s['pierced_faces_by_round'])} -> {s['pierced_faces']} "
            f"({v.get('pierced_after', '?')}) "
            f"| {s['penetrating_vertices']} "
            f"| {s['face_clearance_m'] * 1e3:.3f} / {s['vertex_clearance_m'] * 1e3:.3f} |")
    return "\n".join(rows)


def m1_table(steps, texts):
    rows = [
        "| step | patches refined (by rule) | M1 faces (M0) | new vertices tested / inside "
        "| M1 crossing edges before -> per round -> after | M1 pierced faces before -> after "
        "| inside / crossing / pierced after (brute force) | cut lines |",
        "|---|---|---|---|---|---|---|---|",
    ]
    known = {"patches": "?", "m0_faces": "?"}
    for s in steps:
        known.update({k: s[k] for k in known if k in s})
        if "m1_faces" not in s:
            continue
        refined = dict(s["m1_patches_refined"])
        total = refined.pop("total", 0)
        rules = ", ".join(f"{k} {n}" for k, n in refined.items())
        rounds = ", ".join(str(r) for r in s["m1_crossing_edges_by_round"])
        rows.append(
            f"| {s['step']} `{texts.get(s['step'], s['op'])}` | {total} of {known['patches']} ({rules}) "
            f"| {s['m1_faces']} ({known['m0_faces']}) | {s['m1_new_vertices_tested']} / {s['m1_hits']} "
            f"| {s['m1_crossing_edges_before']} -> {rounds} -> {s['m1_crossing_edges']} "
            f"| {s['m1_pierced_faces_before']} -> {s['m1_pierced_faces']} "
            f"| {s['m1_penetrating_vertices']} / {s['m1_crossing_edges']} / {s['m1_pierced_faces']} "
            f"({s.get('m1_verify', {}).get('inside', '?')} / {s.get('m1_verify', {}).get('crossing', '?')} / "
            f"{s.get('m1_verify', {}).get('pierced', '?')}) "
            f"| {s['m1_cut_lines']} |")
    return "\n".join(rows)


def m1_bench():
    """`cargo bench --bench m1` on two bodies (times vary run to run: not checked)."""
    out = []
    for body in ["female-young-average", "female-old-heavy"]:
        run = subprocess.run(["cargo", "bench", "--quiet", "--bench", "m1", "--", body],
                             cwd=ROOT, check=True, capture_output=True, text=True)
        out.append(run.stdout.strip())
    return "\n\n".join(out)


def collision_bench():
    """`cargo bench --bench collision`: detection modes and point-face against line-line,
    times beside what each found and missed (times vary: written with --bench only)."""
    run = subprocess.run(["cargo", "bench", "--quiet", "--bench", "collision"],
                         cwd=ROOT, check=True, capture_output=True, text=True)
    return re.sub(r"^## ", "#### ", run.stdout.strip(), flags=re.M)


def nurbs_experiment():
    """`drape nurbs-experiment --json`: the L/T table with the true distances (times vary run
    to run: written with --bench only)."""
    with tempfile.TemporaryDirectory() as tmp:
        run = subprocess.run([*drape(), "nurbs-experiment", "--json",
                              "--save", os.path.join(tmp, "n.rrd")],
                             cwd=ROOT, check=True, capture_output=True, text=True)
    out = json.loads(run.stdout)
    rows = ["| L | time ms | query ms | hull pairs tested | leaf pairs | cp min distance mm (paper's mind) "
            "| true distance mm | error mm | net deviation mm (butterfly / leaf) | coverage mm (butterfly / leaf) |",
            "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in out["levels"]:
        rows.append(f"| {r['level']} | {r['time_ms']:.2f} | {r['query_ms']:.2f} | {r['pairs_tested']} | "
                    f"{r['leaf_pairs']} | {r['cp_min_distance_m'] * 1e3:.4f} | {r['true_distance_m'] * 1e3:.4f} | "
                    f"{r['error_m'] * 1e3:+.4f} | {r['net_deviation_m'][0] * 1e3:.4f} / "
                    f"{r['net_deviation_m'][1] * 1e3:.4f} | {r['coverage_m'][0] * 1e3:.3f} / "
                    f"{r['coverage_m'][1] * 1e3:.3f} |")
    rec = out["recommended"]
    rows.append("")
    rows.append(f"Recommended for an accuracy of {rec['accuracy_m'] * 1e3:.1f} mm: **L = {rec['level']}, "
                f"T = {rec['threshold_m'] * 1e3:.3f} mm**.")
    rows.append("")
    rows.append("| L | crossing detected (drape) | paper's rule (cp min < T) | candidate leaf pairs | cp min mm | refined mm |")
    rows.append("|---:|---|---|---:|---:|---:|")
    for c in out["crossing"]:
        rows.append(f"| {c['level']} | {'yes' if c['detected'] else 'NO'} | {'yes' if c['paper_rule'] else 'no'} | "
                    f"{c['candidate_pairs']} | {c['cp_min_distance_m'] * 1e3:.4f} | {c['true_distance_m'] * 1e3:.4f} |")
    return "\n".join(rows)


def sculpt_compare_json(body=None):
    with tempfile.TemporaryDirectory() as tmp:
        cmd = [*drape(), "sculpt-compare", "--json",
               "--save", os.path.join(tmp, "s.rrd")]
        if body:
            cmd += ["--body", body]
        run = subprocess.run(cmd, cwd=ROOT, check=True, capture_output=True, text=True)
    return json.loads(run.stdout)


def sculpt_rows(out):
    variants = [("none", out["none"]), ("uniform", out["uniform"]), ("adaptive", out["adaptive"]),
                ("adaptive at uniform's max edge", out["adaptive"]["at_uniform_max_edge"])]
    return variants


def sculpt_compare():
    """`drape sculpt-compare --json` on every shipped body (times left out: --bench)."""
    rows = ["| body | | faces | region faces | max edge mm | min angle deg | smoothness deg | max turn deg | levels |",
            "|---|---|---:|---:|---:|---:|---:|---:|---:|"]
    paths = [os.path.join(ROOT, "assets", "bodies", f) for f in sorted(os.listdir(os.path.join(ROOT, "assets", "bodies")))
             if f.endswith(".obj")]
    for path in paths:
        out = sculpt_compare_json(path)
        name = os.path.basename(path)[:-4]
        for label, v in sculpt_rows(out):
            rows.append(f"| {name} | {label} | {v['faces']} | {v['region_faces']} | {v['max_edge_m'] * 1e3:.2f} | "
                        f"{v['min_angle_deg']:.1f} | {v['smoothness']:.2f} | {v['max_turn_deg']:.1f} | {v['levels']} |")
            name = ""
    return "\n".join(rows)


def sculpt_times():
    """`drape sculpt-compare --json` on the built-in body: the median times."""
    out = sculpt_compare_json()
    rows = ["| | faces | time ms |", "|---|---:|---:|"]
    for label, v in sculpt_rows(out):
        rows.append(f"| {label} | {v['faces']} | {v['time_ms']:.2f} |")
    return "\n".join(rows)


def logging_budget():
    """The demo at each log detail: compute and logging time summed over its steps, and the
    recording's size (times vary run to run: written with --bench only)."""
    rows = ["| `--log-detail` | compute ms | logging ms | logging / compute | recording MB |",
            "|---|---:|---:|---:|---:|"]
    with tempfile.TemporaryDirectory() as tmp:
        for detail in ["all", "final", "metrics"]:
            rrd, metrics = os.path.join(tmp, f"{detail}.rrd"), os.path.join(tmp, f"{detail}.json")
            subprocess.run([*drape(), "run", "--log-detail", detail,
                            "--metrics", metrics, "--save", rrd], cwd=ROOT, check=True, stderr=subprocess.DEVNULL)
            steps = json.load(open(metrics))
            compute = sum(v for st in steps for k, v in st["timings_ms"].items() if not k.startswith("log."))
            log = sum(v for st in steps for k, v in st["timings_ms"].items() if k.startswith("log."))
            rows.append(f"| {detail} | {compute:.0f} | {log:.0f} | {log / compute:.2f} | {os.path.getsize(rrd) / 1e6:.1f} |")
    return "\n".join(rows)


STRESS_SESSIONS, STRESS_STEPS = 10, 8


def stress_verified():
    """`drape stress --verify` over every shipped body, one shard per core (one worker thread
    each), merged: detection, the partial quality check and the skips against the
    brute-force truth and against the full versions (its times vary: --stress only)."""
    drape = built()
    shards = max(1, os.cpu_count() or 1)
    with tempfile.TemporaryDirectory() as tmp:
        reports = [os.path.join(tmp, f"{i}.json") for i in range(shards)]
        runs = [subprocess.Popen([drape, "--threads", "1", "stress", "--bodies", "assets/bodies",
                                  "--sessions", str(STRESS_SESSIONS), "--steps", str(STRESS_STEPS), "--verify",
                                  "--shard", f"{i}/{shards}", "--report", reports[i],
                                  "--out", os.path.join(tmp, "found")],
                                 cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
                for i in range(shards)]
        for run in runs:
            if run.wait() != 0:
                sys.exit("drape stress found a bug: run it without the script to see it")
        merged = subprocess.run([drape, "stress", "merge", "--json", *reports], cwd=ROOT, check=True,
                                capture_output=True, text=True)
    return verified_table(json.loads(merged.stdout),
                          f"`drape --threads 1 stress --bodies assets/bodies --sessions {STRESS_SESSIONS} "
                          f"--steps {STRESS_STEPS} --verify`, {shards} shards merged:")


def verified_table(out, title):
    """The verified sweep's table from a merged `drape stress --json` report, under `title`."""
    rows = [title,
            "",
            "| body | collisions | vertices / edges checked | inside (truth) | missed: on the skin / line-line / "
            "skipped / point-face | false hits | verdicts the skips changed | quality wrong | partial unlike full "
            "| quality check ms, median partial / full | partial / full, all steps |",
            "|---|---:|---:|---:|---|---:|---:|---:|---:|---:|---:|"]
    for name, t in [*sorted(out["bodies"].items()), ("all", out["overall"])]:
        v = t["verified"]
        rows.append(f"| {name.removesuffix('.obj')} | {v['collisions']} | {v['vertices']} / {v['edges']} | "
                    f"{v['inside']} | {v['missed']}: {v['missed_by']['on_skin']} / {v['missed_by']['line_line']} / "
                    f"{v['missed_by']['untested']} / {v['missed_by']['point_face']} | {v['false_hits']} | "
                    f"{v['skips_changed']} | {v['wrong_quality']} | {v['partial_differs']} | "
                    f"{v['quality_ms']['median']:.2f} / {v['full_quality_ms']['median']:.2f} | "
                    f"{v['time_ratio']:.2f}x |")
    return "\n".join(rows)


def busiest_step(steps):
    s = max((s for s in steps if "hits" in s), key=lambda s: s["hits"])
    parts = ", ".join(f"{k} {n}" for k, n in s["hits_by_partition"].items() if n)
    rules = ", ".join(f"{k.replace('_', ' ')} {n}" for k, n in s["responses_by_rule"].items())
    return (f"Step {s['step']} has the most hits; by partition: {parts}; moves by rule: {rules}. "
            f"Response ease {s['response_ease_m'] * 1e3:.2f} mm; the pushed vertices stand "
            f"{s['max_ease_error_m'] * 1e3:.4f} mm from their gap at most.")


def landmarks(steps):
    scene = steps[0]
    heights = {}
    for l in scene["landmarks"]:
        heights.setdefault(l["kind"], []).append(l["point"][1])
    order = ["ankle", "knee", "crotch", "hip", "waist", "bust", "armpit", "shoulder", "front_neck", "side_neck", "neck"]
    listed = ", ".join(
        f"{k.replace('_', ' ')} {sum(heights[k]) / len(heights[k]):.3f}" for k in order if k in heights)
    waist = next((r for r in scene["rings"] if r["name"] == "waist"), None)
    tape = f"; waist tape girth {waist['tape_girth']:.3f} m" if waist else ""
    return f"On the shipped body: {listed} m{tape}."


def bodies_tables():
    """The demo and the drag session on every shipped body (scripts/body_figures.py)."""
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import body_figures

    drape = built()
    out = []
    for name in ["demo", "drags"]:
        session = os.path.join("assets", "sessions", f"{name}.drape")
        out.append(f"`{session}`:\n\n" + body_figures.summary(drape, session))
    return "\n\n".join(out)


def arms_table():
    """The arms' figures on every shipped body (scripts/body_figures.py)."""
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import body_figures

    return body_figures.arms_table(built())


def sections(steps):
    texts = step_texts()
    return {
        "demo-collision": collision_table(steps, texts),
        "demo-m1": m1_table(steps, texts),
        "demo-busiest": busiest_step(steps),
        "landmarks": landmarks(steps),
        "bodies": bodies_tables(),
        "arms": arms_table(),
        "sculpt-compare": sculpt_compare(),
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--check", action="store_true", help="exit 1 if a page is out of date")
    ap.add_argument("--metrics", help="a metrics file of the demo run with --verify (default: run it)")
    ap.add_argument("--binary", help="the drape binary to run (default: cargo run --release)")
    ap.add_argument("--bench", action="store_true",
                    help="also rewrite the M1 benchmark table (cargo bench --bench m1; its times vary, so "
                         "--check leaves it out)")
    ap.add_argument("--stress", action="store_true",
                    help="also rewrite the verified stress table (drape stress --verify on every shipped body, "
                         "about 20 minutes on 2 cores; its times vary, so --check leaves it out)")
    args = ap.parse_args()
    global BINARY
    BINARY = args.binary
    steps = json.load(open(args.metrics)) if args.metrics else demo_metrics()
    generated = sections(steps)
    if args.bench:
        generated["m1-bench"] = m1_bench()
        generated["collision-bench"] = collision_bench()
        generated["logging"] = logging_budget()
        generated["nurbs-experiment"] = nurbs_experiment()
        generated["sculpt-times"] = sculpt_times()
    if args.stress:
        generated["stress-verified"] = stress_verified()
    stale = []
    for path in doc_files():
        text = path.read_text()
        new = text
        for name, body in generated.items():
            if f"<!-- figures:{name} -->" in new:
                new = splice_text(new, name, body)
        if new != text:
            stale.append(path)
            if not args.check:
                path.write_text(new)
    missing = [n for n in generated if not any(f"<!-- figures:{n} -->" in p.read_text() for p in doc_files())]
    if missing:
        sys.exit(f"no page holds the sections {', '.join(missing)}")
    names = ", ".join(str(p.relative_to(ROOT_PATH)) for p in stale)
    if not stale:
        print("generated figures are current")
        return 0
    if args.check:
        print(f"generated figures are out of date in {names}: run python3 scripts/readme_figures.py")
        return 1
    print(f"generated figures rewritten in {names}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
