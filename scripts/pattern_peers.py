#!/usr/bin/env python3
"""The pattern pieces on every shipped body, and libigl's flattening beside drape's on
exactly the same panels.

For each body it runs the jumpsuit demo (assets/sessions/demo.drape: dimension edits,
drags, a yoke cut) and the shirt session (assets/sessions/shirt.drape: long sleeves, a
stand collar, a cut across the sleeve) with `drape run --patterns DIR` and reads the last
step's patterns JSON: pieces, edge strain max and mean, area ratio, flipped triangles,
seams and their worst mismatch.
Then, on one core (`taskset -c 0` for drape, this process pinned to core 0 for libigl),
every panel OBJ of the first garment step is flattened by `drape flatten --json` (LSCM, then ARAP with a free
boundary, to its own convergence) and by libigl (Python `igl`: `lscm` with two boundary
pins, scaled to the 3D area, then `arap_precomputation` + `arap_solve` with as many
iterations as drape took on that panel, one vertex pinned): the same question, the same
start, the same work. Times are the fastest of 3 runs of each.

    python3 scripts/pattern_peers.py [--binary target/release/drape] [--write]

Needs `igl` and `numpy` in the tools venv (`pip install libigl`); run it with that python:
    ~/.cache/drape-tools/venv/bin/python scripts/pattern_peers.py --write
With --write the tables go into docs/patterns.md (`figures:pattern-bodies`,
`figures:pattern-peers`, and per piece and seam on the built-in body `figures:pattern-detail`).
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from harness import ONE_CORE, ROOT, splice  # noqa: E402

GARMENTS = [("jumpsuit", "jumpsuit fit=tight"), ("shirt", "shirt sleeves=long collar=stand")]
SESSIONS = [("jumpsuit", "assets/sessions/demo.drape"), ("shirt", "assets/sessions/shirt.drape")]
SESSION = "drape 1\nbody builtin\nunits m\npatterns\ngarment {garment} resolution={resolution}\n"


def load_obj(path):
    import numpy as np

    v, f = [], []
    for line in open(path):
        s = line.split()
        if not s:
            continue
        if s[0] == "v":
            v.append([float(x) for x in s[1:4]])
        elif s[0] == "f":
            f.append([int(x.split("/")[0]) - 1 for x in s[1:4]])
    return np.array(v), np.array(f, dtype=np.int64)


def strain(v, f, u):
    import numpy as np

    e = np.sort(np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]]), axis=1)
    e = np.unique(e, axis=0)
    l3 = np.linalg.norm(v[e[:, 0]] - v[e[:, 1]], axis=1)
    l2 = np.linalg.norm(u[e[:, 0]] - u[e[:, 1]], axis=1)
    s = np.abs(l2 - l3) / l3
    return float(s.max()), float(s.mean())


def flipped(f, u):
    a = u[f[:, 1]] - u[f[:, 0]]
    b = u[f[:, 2]] - u[f[:, 0]]
    return int(((a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]) <= 0).sum())


def igl_flatten(v, f, iterations):
    """libigl: LSCM pinned at two boundary vertices half the loop apart, scaled to the 3D
    area, then ARAP from it for `iterations` iterations with one vertex pinned."""
    import igl
    import numpy as np

    loop = igl.boundary_loop(f)
    b = np.array([loop[0], loop[len(loop) // 2]], dtype=np.int64)
    d = float(np.linalg.norm(v[b[0]] - v[b[1]]))
    uv, _ = igl.lscm(v, f, b, np.array([[0.0, 0.0], [d, 0.0]]))
    uv = uv * np.sqrt(igl.doublearea(v, f).sum() / np.abs(igl.doublearea(uv, f)).sum())
    if iterations == 0:
        return uv
    data = igl.ARAPData()
    data.max_iter = int(iterations)
    pin = np.array([loop[0]], dtype=np.int32)
    igl.arap_precomputation(v, f, 2, pin, data)
    return igl.arap_solve(uv[pin], data, uv)


def fastest(fn, runs=3):
    best, out = float("inf"), None
    for _ in range(runs):
        t = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t)
    return best * 1e3, out


def detail(binary, resolution):
    """Per piece and per seam, the jumpsuit and the shirt on the built-in body."""
    out = []
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        for short, garment in GARMENTS:
            session = tmp / f"{short}.drape"
            session.write_text(SESSION.format(garment=garment, resolution=resolution))
            subprocess.run([binary, "run", session, "--patterns", tmp / short, "--save", tmp / "run.rrd"],
                           cwd=ROOT, check=True, capture_output=True)
            doc = json.loads(next((tmp / short).glob("step01_*_patterns.json")).read_text())
            out.append(f"**{short}** (built-in body, resolution {resolution}): pieces\n")
            out.append("| piece | vertices | strain max % | strain mean % | area ratio min..max | angle max deg | flipped | overlaps |")
            out.append("|---|---|---|---|---|---|---|---|")
            for p in doc["panels"]:
                out.append(f"| {p['name']} | {p['vertices']} | {100 * p['max_strain']:.1f} | {100 * p['mean_strain']:.2f} | "
                           f"{p['area_ratio_min']:.2f}..{p['area_ratio_max']:.2f} | {p['max_angle_deg']:.1f} | {p['flipped']} | {p['overlaps']} |")
            out.append(f"\n**{short}**: seams (tolerance 0.5 mm or 0.1% of the length)\n")
            out.append("| seam | curve | 3D length mm | side a mm | side b mm | mismatch mm | sews |")
            out.append("|---|---|---|---|---|---|---|")
            for q in doc["seams"]:
                out.append(f"| {q['name']} | {q['curve']} | {1e3 * q['length_3d_m']:.2f} | {1e3 * q['length_a_m']:.3f} | "
                           f"{1e3 * q['length_b_m']:.3f} | {1e3 * q['mismatch_m']:.4f} | {'yes' if q['sews'] else 'NO'} |")
            out.append("")
    return "\n".join(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--binary", default=str(ROOT / "target/release/drape"))
    ap.add_argument("--resolution", type=int, default=6)
    ap.add_argument("--write", action="store_true")
    args = ap.parse_args()
    os.sched_setaffinity(0, {0})
    bodies = sorted((ROOT / "assets/bodies").glob("*.obj"))
    body_rows, peer_rows = [], []
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        for body in bodies:
            for short, session in SESSIONS:
                out = tmp / f"{body.stem}-{short}"
                subprocess.run([*ONE_CORE, args.binary, "--threads", "1", "run", ROOT / session, "--body", body,
                                "--patterns", out, "--save", tmp / "run.rrd"], cwd=ROOT, check=True,
                               capture_output=True)
                steps = sorted(out.glob("step*_patterns.json"))
                first_step = steps[0].name.split("_", 1)[0]
                doc = json.loads(steps[-1].read_text())
                panels, seams = doc["panels"], doc["seams"]
                body_rows.append((body.stem, short, len(panels),
                                  100 * max(p["max_strain"] for p in panels),
                                  100 * sum(p["mean_strain"] for p in panels) / len(panels),
                                  min(p["area_ratio_min"] for p in panels), max(p["area_ratio_max"] for p in panels),
                                  sum(p["flipped"] for p in panels), len(seams),
                                  1e3 * max(s["mismatch_m"] for s in seams), sum(not s["sews"] for s in seams)))
                body_rows[-1] = (*body_rows[-1], steps[-1].name.split("_", 1)[0])
                first = json.loads(steps[0].read_text())
                objs = sorted(out.glob(f"{first_step}_*_panel_*.obj"))
                lines = subprocess.run([*ONE_CORE, args.binary, "flatten", "--json", "--runs", "3", *objs],
                                       cwd=ROOT, check=True, capture_output=True, text=True).stdout.splitlines()
                drape = {Path(r["panel"]).name: r for r in map(json.loads, lines)}
                sewn = {p["name"]: p for p in first["panels"]}
                for obj in objs:
                    v, f = load_obj(obj)
                    d = drape[obj.name]
                    ms, uv = fastest(lambda: igl_flatten(v, f, d["iterations"]))
                    ms_lscm, uv_lscm = fastest(lambda: igl_flatten(v, f, 0))
                    name = obj.stem.split("_panel_", 1)[1]
                    peer_rows.append((body.stem, short, name, len(v), d["ms"], ms, ms_lscm,
                                      100 * d["max_strain"], 100 * d["mean_strain"],
                                      *[100 * x for x in strain(v, f, uv)],
                                      *[100 * x for x in strain(v, f, uv_lscm)],
                                      100 * sewn[name]["max_strain"], 100 * sewn[name]["mean_strain"],
                                      d["flipped"], flipped(f, uv)))
                print(f"{body.stem} {short}: {len(objs)} panels", file=sys.stderr)
    table = ["| body | session | last step | pieces | strain max % | strain mean % | area ratio min..max | flipped | seams | worst mismatch mm | over tolerance |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in body_rows:
        table.append(f"| {r[0]} | {r[1]} | {r[11]} | {r[2]} | {r[3]:.1f} | {r[4]:.2f} | {r[5]:.2f}..{r[6]:.2f} | {r[7]} | {r[8]} | {r[9]:.4f} | {r[10]} |")
    bodies_md = "\n".join(table)
    # Peers: per body and garment, the panels' sums of time and the strain over them.
    agg = {}
    for r in peer_rows:
        a = agg.setdefault((r[0], r[1]), [0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0, 0])
        a[0] += 1
        a[1] += r[4]
        a[2] += r[5]
        a[3] += r[6]
        a[4] = max(a[4], r[7]); a[5] += r[8]
        a[6] = max(a[6], r[9]); a[7] += r[10]
        a[8] = max(a[8], r[11]); a[9] += r[12]
        a[10] = max(a[10], r[13]); a[11] += r[14]
        a[12] += r[15]; a[13] += r[16]
    peers = ["| body | garment | panels | drape LSCM+ARAP ms | libigl LSCM+ARAP ms | ratio | libigl LSCM ms | strain max/mean %: drape ARAP | libigl ARAP | libigl LSCM | drape sewn | flipped drape/libigl |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for (b, g), a in agg.items():
        n = a[0]
        peers.append(f"| {b} | {g} | {n} | {a[1]:.1f} | {a[2]:.1f} | {a[1] / a[2]:.2f}x | {a[3]:.1f} | "
                     f"{a[4]:.1f} / {a[5] / n:.2f} | {a[6]:.1f} / {a[7] / n:.2f} | {a[8]:.1f} / {a[9] / n:.2f} | "
                     f"{a[10]:.1f} / {a[11] / n:.2f} | {a[12]} / {a[13]} |")
    peers_md = "\n".join(peers)
    detail_md = detail(args.binary, args.resolution)
    print(bodies_md)
    print()
    print(peers_md)
    if args.write:
        page = ROOT / "docs/patterns.md"
        splice(page, "pattern-bodies", bodies_md)
        splice(page, "pattern-peers", peers_md)
        splice(page, "pattern-detail", detail_md)


if __name__ == "__main__":
    main()
