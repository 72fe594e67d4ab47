#!/usr/bin/env python3
"""A close-up picture of a drape recording, rendered by the real Rerun viewer, headless.

  python3 scripts/closeup.py OUT.png FILE.rrd --eye X,Y,Z --target X,Y,Z [--size 1000x800]
                             [--contents "+ /body/mesh" ...]

Starts `rerun FILE --headless` (Rerun 0.36.3, CPU Vulkan: `apt-get install mesa-vulkan-drivers`
and `pip install rerun-sdk==0.36.3 pillow`), sends it a blueprint with one 3D view whose camera
stands at --eye looking at --target (y up; the body's front is +z), shows the last stage, and
saves the first screenshot that two captures in a row agree on (--patterns: the pattern pieces
in 2D beside the garment by panel and by strain). The README's crotch pictures:

  drape run assets/sessions/jumpsuit.drape --body assets/bodies/female-old-heavy.obj --save /tmp/g.rrd
  python3 scripts/closeup.py assets/figures/crotch-old-heavy-after.png /tmp/g.rrd \
      --eye 0,0.62,0.40 --target 0,0.73,0.08 --small

and the `before` picture the same with the binary of commit 626da51 (before the every-body work).
"""
from __future__ import annotations

import argparse
import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
from pathlib import Path


def rerun_binary() -> str:
    """The real Rust binary (the `rerun` on PATH in a venv is a Python shim that forks it)."""
    if os.environ.get("RERUN_BIN"):
        return os.environ["RERUN_BIN"]
    try:
        import rerun_cli

        cand = Path(rerun_cli.__file__).with_name("rerun")
        if cand.exists():
            return str(cand)
    except ImportError:
        pass
    found = shutil.which("rerun")
    if not found:
        sys.exit("rerun binary not found (pip install rerun-sdk, or set RERUN_BIN)")
    return found


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def wait_for_png(path: Path, timeout: float = 20.0) -> None:
    """save_screenshot() can return before the viewer has finished writing the file
    (observed: 0 bytes, or a few bytes short). Wait until it is complete and decodable."""
    from PIL import Image

    deadline, last = time.time() + timeout, -1
    while time.time() < deadline:
        size = path.stat().st_size if path.exists() else -1
        if size > 0 and size == last:
            try:
                with Image.open(path) as im:
                    im.load()
                return
            except OSError:
                pass
        last = size
        time.sleep(0.1)
    raise RuntimeError(f"screenshot {path} was never completely written")


def same_pixels(a: Path, b: Path) -> bool:
    from PIL import Image

    with Image.open(a) as ia, Image.open(b) as ib:
        return ia.size == ib.size and ia.tobytes() == ib.tobytes()


def shrink(png: Path) -> None:
    """The 3D view alone, 70% size, 256 colours: a picture small enough to commit."""
    from PIL import Image

    im = Image.open(png).convert("RGB")
    w, h = im.size
    view = im.crop((0, 52, w, h - 200))  # the viewer's top bar and its collapsed time panel
    view = view.resize((int(view.width * 0.7), int(view.height * 0.7)), Image.LANCZOS)
    view.quantize(colors=256, method=Image.Quantize.FASTOCTREE).save(png, optimize=True)


def recording_id(rrd: str) -> str:
    """The recording id of an .rrd (the blueprint must name it to apply to it)."""
    text = subprocess.run([rerun_binary(), "rrd", "print", rrd], capture_output=True, text=True).stdout
    lines = text.splitlines()
    for i, line in enumerate(lines):
        if "Recording," in line and i + 2 < len(lines):
            return lines[i + 2].strip().strip('",')
    raise RuntimeError(f"no recording id in {rrd}")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out", help="the PNG to write")
    ap.add_argument("rrd", help="a recording drape wrote")
    ap.add_argument("--size", default="1000x800", help="viewer size in points, WxH")
    ap.add_argument("--view-id", help="capture only this view (a view UUID)")
    ap.add_argument("--timeout", type=float, default=120.0)
    ap.add_argument("--interval", type=float, default=0.5, help="seconds between screenshots")
    ap.add_argument("--min-wait", type=float, default=1.0, help="never accept a screenshot earlier")
    ap.add_argument("--renderer", default="vulkan", help="vulkan (lavapipe works); gl fails on llvmpipe")
    ap.add_argument("--keep-log", action="store_true")
    ap.add_argument("--small", action="store_true",
                    help="keep only the 3D view (drop the viewer's top bar and time panel), 70%% size, 256 colours")
    ap.add_argument("--eye", required=True)
    ap.add_argument("--target", required=True)
    ap.add_argument("--contents", nargs="*", default=["+ /body/mesh", "+ /garment/m0/**", "+ /collision/mesh/**", "+ /collision/guarantee"])
    ap.add_argument("--patterns", action="store_true",
                    help="the pattern pieces in 2D beside the garment by panel and by strain (both from --eye)")
    ap.add_argument("--text", nargs="*", default=[],
                    help="text documents to show beside the 3D view (entity paths, e.g. /legend/partitions)")
    a = ap.parse_args()

    from rerun.experimental import ViewerClient

    out = Path(a.out).resolve()
    out.parent.mkdir(parents=True, exist_ok=True)
    work = Path(tempfile.mkdtemp(prefix="rrshot-"))
    log_path = work / "viewer.log"
    env = dict(os.environ)
    # INFO logs become toasts drawn over the screenshot -> keep only warnings, and drop the
    # "software rasterizer" warnings that lavapipe always triggers.
    env.setdefault("RUST_LOG", "warn,re_renderer::context=error,egui_wgpu=error")
    if not os.path.isdir(env.get("XDG_RUNTIME_DIR", "")):
        xdg = work / "xdg"
        xdg.mkdir(mode=0o700)
        env["XDG_RUNTIME_DIR"] = str(xdg)  # silences "XDG_RUNTIME_DIR is invalid" spam

    port = free_port()
    cmd = [rerun_binary(), str(Path(a.rrd).resolve()), "--headless",
           "--renderer", a.renderer, "--port", str(port), "--window-size", a.size]
    with open(log_path, "wb") as log:
        viewer = subprocess.Popen(cmd, env=env, stdout=log, stderr=subprocess.STDOUT,
                                  start_new_session=True)
    rc = 1
    try:
        t0 = time.time()
        while True:  # wait for the gRPC port
            if viewer.poll() is not None:
                raise RuntimeError(f"viewer exited with {viewer.returncode}")
            try:
                socket.create_connection(("127.0.0.1", port), timeout=0.2).close()
                break
            except OSError:
                if time.time() - t0 > a.timeout:
                    raise RuntimeError("viewer never opened its port")
                time.sleep(0.1)
        client = ViewerClient.connect(f"rerun+http://127.0.0.1:{port}/proxy")
        import rerun as rr
        import rerun.blueprint as rrb
        time.sleep(3.0)
        eye = [float(x) for x in a.eye.split(",")]
        tgt = [float(x) for x in a.target.split(",")]
        view = rrb.Spatial3DView(name="close", origin="/", contents=a.contents,
                                 eye_controls=rrb.EyeControls3D(position=eye, look_target=tgt, eye_up=[0.0, 1.0, 0.0]))
        if a.patterns:
            def eye_view(name, contents):
                return rrb.Spatial3DView(name=name, origin="/", contents=contents,
                                         eye_controls=rrb.EyeControls3D(position=eye, look_target=tgt, eye_up=[0.0, 1.0, 0.0]))
            view = rrb.Horizontal(
                rrb.Spatial2DView(name="Patterns", origin="/patterns/pieces"),
                rrb.Vertical(eye_view("Panels", ["+ /body/mesh", "+ /patterns/garment/panels"]),
                             eye_view("Pattern strain", ["+ /patterns/garment/strain"])),
                column_shares=[2, 1])
        if a.text:
            docs = [rrb.TextDocumentView(name=t.rsplit("/", 1)[-1], origin=t) for t in a.text]
            view = rrb.Horizontal(view, rrb.Vertical(*docs), column_shares=[3, 2])
        bp = rrb.Blueprint(
            view,
            rrb.TimePanel(timeline="stage", play_state="following"),
            collapse_panels=True,
        )
        rr.init("drape", recording_id=recording_id(a.rrd))
        rr.connect_grpc(f"rerun+http://127.0.0.1:{port}/proxy")
        rr.send_blueprint(bp, make_active=True, make_default=True)
        time.sleep(1.0)
        prev = None
        i = 0
        while True:
            shot = work / f"shot_{i}.png"
            client.save_screenshot(str(shot), a.view_id)
            wait_for_png(shot)
            if viewer.poll() is not None:
                raise RuntimeError(f"viewer exited with {viewer.returncode}")
            elapsed = time.time() - t0
            if prev is not None and elapsed >= a.min_wait and same_pixels(prev, shot):
                shutil.copyfile(shot, out)
                if a.small:
                    shrink(out)
                print(f"wrote {out} (stable after {elapsed:.1f}s, {i + 1} screenshots)")
                rc = 0
                break
            if elapsed > a.timeout:
                shutil.copyfile(shot, out)
                print(f"WARNING: not stable after {elapsed:.0f}s; wrote last screenshot to {out}", file=sys.stderr)
                rc = 2
                break
            prev, i = shot, i + 1
            time.sleep(a.interval)
    except Exception as e:  # noqa: BLE001
        print(f"ERROR: {e}\n--- viewer log ({log_path}) ---", file=sys.stderr)
        print(log_path.read_text(errors="replace")[-4000:], file=sys.stderr)
        rc = 1
    finally:
        if viewer.poll() is None:  # stop only the viewer process group we started
            os.killpg(viewer.pid, signal.SIGTERM)
            try:
                viewer.wait(timeout=10)
            except subprocess.TimeoutExpired:
                os.killpg(viewer.pid, signal.SIGKILL)
                viewer.wait()
        if rc == 0 and not a.keep_log:
            shutil.rmtree(work, ignore_errors=True)
        elif rc != 0 or a.keep_log:
            print(f"(work dir kept: {work})", file=sys.stderr)
    return rc


if __name__ == "__main__":
    sys.exit(main())
