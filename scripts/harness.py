"""What the figure scripts share: runs of the binary pinned to cores, their --metrics, and the
splicing of a generated section into a Markdown file.

    from harness import ROOT, pinned, run_metrics, runs_and_binary, splice, median, section_file

A generated section sits between `<!-- figures:NAME -->` and `<!-- /figures:NAME -->`; nothing
else in the file is touched. Standard library only.
"""
import json
import re
import statistics
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
ONE_CORE = ["taskset", "-c", "0"]


def pinned(binary, *args, threads=1):
    """The command line of `binary --threads N ARGS`, on one core (`taskset -c 0`) for one
    thread: each side of a comparison on the same number of cores."""
    return [*(ONE_CORE if threads == 1 else []), str(binary), "--threads", str(threads), *map(str, args)]


def run_metrics(binary, folder, *args, threads=1):
    """Runs `binary --threads N ARGS run ...` pinned (`args` holds the command and its
    arguments, `run SESSION ...`), writing its metrics and recording into `folder`; returns
    the metrics, one object per step."""
    folder = Path(folder)
    metrics = folder / "metrics.json"
    subprocess.run(pinned(binary, *args, "--metrics", metrics, "--save", folder / "run.rrd", threads=threads),
                   cwd=ROOT, capture_output=True, check=True)
    return json.loads(metrics.read_text())


def runs_and_binary(description=None):
    """An argument parser with what the timing scripts share: `--runs N` (default 3) and
    `--binary PATH` (default target/release/drape)."""
    import argparse
    ap = argparse.ArgumentParser(description=description)
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--binary", default=str(ROOT / "target/release/drape"))
    return ap


def median(values):
    """The median, NaN for none."""
    return statistics.median(values) if values else float("nan")


def splice_text(text, name, body):
    """`text` with the section `name` holding `body`; None when it has no such section."""
    pattern = re.compile(rf"(<!-- figures:{re.escape(name)} -->\n)(?:.*?\n)?(<!-- /figures:{re.escape(name)} -->)",
                         re.S)
    if not pattern.search(text):
        return None
    return pattern.sub(lambda m: m.group(1) + body.strip("\n") + "\n" + m.group(2), text)


def doc_files():
    """The pages generated sections live in: the README and every page under docs/."""
    return [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]


def section_file(name):
    """The page that holds the section `name`; exits when none does."""
    marker = f"<!-- figures:{name} -->"
    for path in doc_files():
        if marker in path.read_text():
            return path
    sys.exit(f"no page holds a section figures:{name}")


def splice(path, name, body):
    """Writes `body` into the section `name` of the file `path` (None: the page that holds
    it); exits when it has none."""
    path = section_file(name) if path is None else Path(path)
    text = splice_text(path.read_text(), name, body)
    if text is None:
        sys.exit(f"{path.name} has no section figures:{name}")
    path.write_text(text)
    print(f"{path.name}: figures:{name} rewritten")
