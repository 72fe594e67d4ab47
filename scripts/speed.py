#!/usr/bin/env python3
"""drape's speed table, measured in one run, with the closest-point peers beside it.

    python3 scripts/speed.py [--json OUT] [--skip-sessions] [--readme]

What it does, in order (every drape figure on one worker thread and pinned to one core
with `taskset -c 0`, unless the row says 2 threads):

1. Makes a local venv (~/.cache/drape-tools/peers) with the peers, FCPW and libigl, the
   first time.
2. `cargo bench --bench speed -- --export DIR`: drape's own query times, parry3d's, the
   scaling tables, and the points of the demo's garment at resolutions 6 and 24 with the
   body and drape's answers (signed distance, inside).
3. Times FCPW (`find_closest_points`, `contains`) and libigl (`signed_distance`,
   pseudo-normal sign) on exactly those points and that body, on one core, then on every
   core, and checks their inside verdicts and distances against drape's.
4. Runs the demo session (resolution 6) and the same session at resolution 24 with
   `drape run --threads 1 --metrics`, and the same with 2 threads, each `--session-runs`
   times (default 3; a drag step's figure is the median over every drag of every run), and
   reads the per-step compute and logging times.
5. Prints one table: each figure beside its goal and the peer ratios (with --readme, also
   writes everything it printed into README.md between `<!-- figures:speed -->` and
   `<!-- /figures:speed -->`).
"""

import argparse
import json
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from harness import ONE_CORE, ROOT, median, pinned, splice

VENV = Path.home() / ".cache" / "drape-tools" / "peers"
PEERS = ["numpy==2.4.6", "fcpw==1.2.0", "libigl==2.6.3"]


LINES = []


def emit(line=""):
    """Prints a line of the report (and keeps it for the README)."""
    print(line, flush=True)
    LINES.append(line)


def venv_python() -> Path:
    py = VENV / "bin" / "python"
    if not py.exists():
        print(f"making the peers' venv in {VENV} ...", file=sys.stderr)
        subprocess.run([sys.executable, "-m", "venv", str(VENV)], check=True)
        subprocess.run([str(py), "-m", "pip", "install", "-q", *PEERS], check=True)
    return py


# The peers' side, run in the venv (one process per core setting).
PEER_CODE = r"""
import json, sys, time
import numpy as np
import fcpw, igl

folder, names = sys.argv[1], sys.argv[2].split(",")
V = np.fromfile(f"{folder}/body.vertices.f64", dtype="<f8").reshape(-1, 3)
F = np.fromfile(f"{folder}/body.triangles.u32", dtype="<u4").reshape(-1, 3)

def median_s(f, runs=7):
    t = []
    for _ in range(runs):
        s = time.perf_counter(); f(); t.append(time.perf_counter() - s)
    return sorted(t)[len(t) // 2]

scene = fcpw.scene_3D()
scene.set_object_count(1)
scene.set_object_vertices(np.asfortranarray(V.astype(np.float32)), 0)
scene.set_object_triangles(np.ascontiguousarray(F.astype(np.int32)), 0)
s = time.perf_counter()
scene.build(fcpw.aggregate_type.bvh_surface_area, True)
fcpw_build = time.perf_counter() - s
Fi = F.astype(np.int64)
out = {"fcpw_build_ms": fcpw_build * 1e3}
for name in names:
    P = np.fromfile(f"{folder}/{name}.points.f64", dtype="<f8").reshape(-1, 3)
    signed = np.fromfile(f"{folder}/{name}.signed.f64", dtype="<f8")
    n = len(P)
    P32 = np.asfortranarray(P.astype(np.float32))
    radii = np.full(n, np.inf, dtype=np.float32)
    hits = fcpw.interaction_3D_list()
    t_closest = median_s(lambda: scene.find_closest_points(P32, radii, hits))
    d = np.array([h.d for h in hits])
    inside = np.zeros(n, dtype=np.int32)
    t_contains = median_s(lambda: scene.contains(P32, inside))
    res = {}
    t_igl = median_s(lambda: res.update(r=igl.signed_distance(P, V, Fi, sign_type=igl.SIGNED_DISTANCE_TYPE_PSEUDONORMAL)), runs=3)
    S = res["r"][0]
    out[name] = {
        "points": n,
        "fcpw_closest_us": t_closest / n * 1e6,
        "fcpw_contains_us": t_contains / n * 1e6,
        "igl_signed_us": t_igl / n * 1e6,
        "fcpw_max_distance_diff_m": float(np.max(np.abs(d - np.abs(signed)))),
        "fcpw_inside_differ": int(np.sum((inside != 0) != (signed < 0))),
        "igl_max_distance_diff_m": float(np.max(np.abs(np.abs(S) - np.abs(signed)))),
        "igl_inside_differ": int(np.sum((S < 0) != (signed < 0))),
    }
print(json.dumps(out))
"""


def run(cmd, **kw):
    return subprocess.run(cmd, check=True, cwd=ROOT, **kw)


def peers(py: Path, folder: Path, names, one_core: bool):
    cmd = ([*ONE_CORE] if one_core else []) + [str(py), "-c", PEER_CODE, str(folder), ",".join(names)]
    return json.loads(run(cmd, capture_output=True, text=True).stdout)


def session_figures(metrics_path: Path):
    """Per-step compute and logging (ms) of a --metrics file, by op."""
    steps = json.loads(metrics_path.read_text())
    out = []
    for s in steps:
        t = s.get("timings_ms", {})
        compute = {k: v for k, v in t.items() if not k.startswith("log.")}
        log = sum(v for k, v in t.items() if k.startswith("log."))
        out.append({"op": s.get("op"), "compute": compute, "log": log, "notes": s.get("notes", [])})
    return out


def garment_ms(step):
    """The garment's part of a step: solve, assembly and M0's collision (M1 apart)."""
    keys = ("constraints.", "garment.", "collision.")
    return sum(v for k, v in step["compute"].items() if k.startswith(keys))


def m1_ms(step):
    return sum(v for k, v in step["compute"].items() if k.startswith("m1."))


def run_session(binary: Path, session: Path, threads: int, folder: Path, tag: str):
    """Runs `session`; body indexes are cached in a folder per thread count, empty at first,
    so that the first run on a body builds (and writes) its index and the next reads it."""
    metrics = folder / f"{tag}.metrics.json"
    cmd = pinned(binary, "--index-cache", folder / f"index-cache-{threads}", "run", session,
                 "--metrics", metrics, "--save", folder / f"{tag}.rrd", threads=threads)
    run(cmd, capture_output=True)
    return session_figures(metrics)




def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--json", type=Path, help="also write every figure here as JSON")
    ap.add_argument("--skip-sessions", action="store_true", help="only the query tables")
    ap.add_argument("--session-runs", type=int, default=3, help="runs of each session (default 3)")
    ap.add_argument("--readme", action="store_true", help="write the report into its page (figures:speed, in docs/)")
    a = ap.parse_args()
    if shutil.which("taskset") is None:
        sys.exit("speed.py needs taskset (util-linux) to pin runs to one core")
    py = venv_python()
    folder = Path(tempfile.mkdtemp(prefix="drape-speed-"))
    run(["cargo", "build", "--release", "-q"])
    binary = ROOT / "target" / "release" / "drape"
    emit("#### drape's queries (`cargo bench --bench speed`, one thread, one core)")
    emit()
    bench = run([*ONE_CORE, "cargo", "bench", "-q", "--bench", "speed", "--", "--export", str(folder), "--json", str(folder / "drape1.json")], capture_output=True, text=True)
    for line in bench.stdout.splitlines():
        emit(line.replace("# drape speed, ", "drape speed, "))
    run(["cargo", "bench", "-q", "--bench", "speed", "--", "--threads", "2", "--json", str(folder / "drape2.json")], capture_output=True)
    d1 = json.loads((folder / "drape1.json").read_text())
    d2 = json.loads((folder / "drape2.json").read_text())
    p1 = peers(py, folder, ["res6", "res24"], one_core=True)
    p2 = peers(py, folder, ["res6", "res24"], one_core=False)
    figures = {"drape_1": d1, "drape_2": d2, "peers_1": p1, "peers_all": p2}

    def row(res):
        return next(g for g in d1["garments"] if g["garment"] == f"M0 resolution {res}")

    def row2(res):
        return next(g for g in d2["garments"] if g["garment"] == f"M0 resolution {res}")

    emit()
    emit("#### Peers on the same points and body (closest point and inside)")
    emit()
    emit("| points | cores | drape exact signed us | drape cold detect us | parry3d us | FCPW closest us | FCPW contains us | libigl signed us | drape / FCPW | inside verdicts differing (FCPW, libigl, parry3d) | max distance diff FCPW, libigl (um) |")
    emit("|---|---|---:|---:|---:|---:|---:|---:|---:|---|---|")
    for res in (6, 24):
        name = f"res{res}"
        for cores, d, p in (("1", row(res), p1[name]), ("2", row2(res), p2[name])):
            emit(
                f"| M0 resolution {res} ({p['points']}) | {cores} | {d['exact_signed_us']:.3f} | {d['cold_detect_us']:.3f} | {d['parry_us']:.3f} | "
                f"{p['fcpw_closest_us']:.3f} | {p['fcpw_contains_us']:.3f} | {p['igl_signed_us']:.3f} | "
                f"{d['exact_signed_us'] / p['fcpw_closest_us']:.2f}x | {p['fcpw_inside_differ']}, {p['igl_inside_differ']}, {d['parry_differing']} | "
                f"{p['fcpw_max_distance_diff_m'] * 1e6:.2f}, {p['igl_max_distance_diff_m'] * 1e6:.2f} |"
            )
    if not a.skip_sessions:
        demo = ROOT / "assets" / "sessions" / "demo.drape"
        text = demo.read_text()
        fine = folder / "demo-24.drape"
        fine.write_text(text.replace("resolution=6", "resolution=24"))
        runs = {}
        for tag, session in (("demo6", demo), ("demo24", fine)):
            for threads in (1, 2):
                runs[f"{tag}.{threads}"] = [
                    run_session(binary, session, threads, folder, f"{tag}.{threads}.{k}")
                    for k in range(max(1, a.session_runs))
                ]
        figures["sessions"] = runs

        def index_ms(tag, how, every=False):
            """The `body.index` time of the first run `tag` (with `every`, the median over all its
            runs), each of which must have `how` (built, read) it."""
            times = []
            for r in runs[tag] if every else runs[tag][:1]:
                step = next(s for s in r if "body.index" in s["compute"])
                if not any(n.startswith(f"body index {how}") for n in step["notes"]):
                    sys.exit(f"{tag}: expected the body index {how}, the run says {step['notes']}")
                times.append(step["compute"]["body.index"])
            return median(times)

        def drags(tag):
            return [s for r in runs[tag] for s in r if s["op"] == "drag" and "garment.assemble" in s["compute"]]

        emit()
        emit(f"#### The table (the demo session and the same at resolution 24; drag steps: its 4 accepted drags, {max(1, a.session_runs)} runs)")
        emit()
        emit("| what | 1 thread, one core | 2 threads | goal |")
        emit("|---|---:|---:|---|")
        for res, goal in ((6, "<= 5 ms on one core"), (24, "<= 40 ms")):
            one, two = drags(f"demo{res}.1"), drags(f"demo{res}.2")
            emit(f"| drag step, resolution {res}: garment (solve, assemble, M0 collision), median ms | {median([garment_ms(s) for s in one]):.1f} | {median([garment_ms(s) for s in two]):.1f} | {goal} |")
            emit(f"| drag step, resolution {res}: M1 (select, subdivide, collide), median ms | {median([m1_ms(s) for s in one]):.1f} | {median([m1_ms(s) for s in two]):.1f} | |")
            emit(f"| drag step, resolution {res}: logging, median ms | {median([s['log'] for s in one]):.1f} | {median([s['log'] for s in two]):.1f} | <= compute |")
        r24 = row(24)
        emit(f"| cold detection per vertex, resolution 24 (us) | {r24['cold_detect_us']:.3f} | {row2(24)['cold_detect_us']:.3f} | <= 0.5 us and <= 0.4x FCPW |")
        emit(f"| the same, over FCPW's closest point on the same cores | {r24['cold_detect_us'] / p1['res24']['fcpw_closest_us']:.2f}x | {row2(24)['cold_detect_us'] / p2['res24']['fcpw_closest_us']:.2f}x | <= 0.4x |")
        emit(f"| body index build, ms | {d1['index_build_ms']:.1f} | {d2['index_build_ms']:.1f} | <= 20 ms or cached |")
        emit(f"| body index read from its cache file, ms | {d1['index_cached_ms']:.1f} | {d2['index_cached_ms']:.1f} | <= 20 ms |")
        emit(f"| a session's body index: first run on the body (built and cached), ms | {index_ms('demo6.1', 'built'):.1f} | {index_ms('demo6.2', 'built'):.1f} | |")
        emit(f"| a session's body index: the next runs (read from the cache; median of {max(1, a.session_runs)}), ms | {index_ms('demo24.1', 'read', True):.1f} | {index_ms('demo24.2', 'read', True):.1f} | <= 20 ms |")
    if a.json:
        a.json.write_text(json.dumps(figures, indent=1))
    if a.readme:
        splice(None, "speed", "\n".join(LINES))
    shutil.rmtree(folder, ignore_errors=True)


if __name__ == "__main__":
    main()
