# The peers' side of `drape bench` (run by it with the peers' Python; embedded in the binary).
#
#   python peers.py FOLDER NAMES NTHREADS
#
# For each NAME (resN) in the comma-separated NAMES, reads the points drape exported into FOLDER
# with the body and drape's answers, and asks every peer the question drape's detection answers
# (is the vertex inside the body, or nearer than the ease?), on NTHREADS threads (0: all):
#   FCPW:    find_closest_points capped at the ease, plus contains (inside)
#   Open3D:  RaycastingScene.compute_signed_distance (Embree)
#   libigl:  signed_distance with pseudo-normal signs
# Prints one JSON object: per name and peer, the median time per point (us) and how many inside
# verdicts differ from drape's exact ones.
import json
import sys
import time

import numpy as np

folder, names, nthreads = sys.argv[1], sys.argv[2].split(","), int(sys.argv[3])
V = np.fromfile(f"{folder}/body.vertices.f64", dtype="<f8").reshape(-1, 3)
F = np.fromfile(f"{folder}/body.triangles.u32", dtype="<u4").reshape(-1, 3)
ease = float(open(f"{folder}/ease.txt").read())
RUNS = 5


def median_s(f, runs=RUNS):
    t = []
    for _ in range(runs):
        s = time.perf_counter()
        f()
        t.append(time.perf_counter() - s)
    return sorted(t)[len(t) // 2]


out = {"versions": {}, "errors": {}}
peers = {}
try:
    import fcpw

    scene = fcpw.scene_3D()
    scene.set_object_count(1)
    scene.set_object_vertices(np.asfortranarray(V.astype(np.float32)), 0)
    scene.set_object_triangles(np.ascontiguousarray(F.astype(np.int32)), 0)
    scene.build(fcpw.aggregate_type.bvh_surface_area, True)
    peers["fcpw"] = scene
    out["versions"]["fcpw"] = getattr(fcpw, "__version__", "installed")
except Exception as e:  # a missing peer is reported, not fatal
    out["errors"]["fcpw"] = repr(e)
try:
    import open3d as o3d

    rc = o3d.t.geometry.RaycastingScene()
    rc.add_triangles(o3d.core.Tensor(V.astype(np.float32)), o3d.core.Tensor(F.astype(np.uint32)))
    peers["open3d"] = rc
    out["versions"]["open3d"] = o3d.__version__
except Exception as e:
    out["errors"]["open3d"] = repr(e)
try:
    import igl

    peers["libigl"] = igl
    out["versions"]["libigl"] = "installed"
except Exception as e:
    out["errors"]["libigl"] = repr(e)

for name in names:
    P = np.fromfile(f"{folder}/{name}.points.f64", dtype="<f8").reshape(-1, 3)
    signed = np.fromfile(f"{folder}/{name}.signed.f64", dtype="<f8")
    truth = signed < 0
    n = len(P)
    row = {"points": n}
    if "fcpw" in peers:
        scene = peers["fcpw"]
        P32 = np.asfortranarray(P.astype(np.float32))
        radii = np.full(n, ease * ease, dtype=np.float32)  # squared: capped at the ease
        hits = fcpw.interaction_3D_list()
        inside = np.zeros(n, dtype=np.int32)
        t_closest = median_s(lambda: scene.find_closest_points(P32, radii, hits))
        t_contains = median_s(lambda: scene.contains(P32, inside))
        row["fcpw_us"] = (t_closest + t_contains) / n * 1e6
        row["fcpw_differ"] = int(np.sum((inside != 0) != truth))
    if "open3d" in peers:
        rc = peers["open3d"]
        Q = o3d.core.Tensor(P.astype(np.float32))
        res = {}
        t = median_s(lambda: res.update(d=rc.compute_signed_distance(Q, nthreads=nthreads)))
        row["open3d_us"] = t / n * 1e6
        row["open3d_differ"] = int(np.sum((res["d"].numpy() < 0) != truth))
    if "libigl" in peers:
        Fi = F.astype(np.int64)
        res = {}
        t = median_s(
            lambda: res.update(r=igl.signed_distance(P, V, Fi, sign_type=igl.SIGNED_DISTANCE_TYPE_PSEUDONORMAL)),
            runs=3,
        )
        row["libigl_us"] = t / n * 1e6
        row["libigl_differ"] = int(np.sum((res["r"][0] < 0) != truth))
    out[name] = row
print(json.dumps(out))
