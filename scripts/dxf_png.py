#!/usr/bin/env python3
"""A picture of a pattern DXF drawn by ezdxf's own renderer (its drawing add-on, through
matplotlib): what another tool makes of drape's DXF, blocks inserted, grain lines, notches
and names. Needs ezdxf and matplotlib in the tools venv (`pip install ezdxf matplotlib`).

    ~/.cache/drape-tools/venv/bin/python scripts/dxf_png.py OUT.png PATTERNS.dxf
"""
import sys

import ezdxf
import matplotlib

matplotlib.use("Agg")
from ezdxf.addons.drawing import matplotlib as draw  # noqa: E402

doc = ezdxf.readfile(sys.argv[2])
errors = doc.audit().errors
draw.qsave(doc.modelspace(), sys.argv[1], bg="#FFFFFF", dpi=110)
print(f"wrote {sys.argv[1]} (ezdxf audit: {len(errors)} errors)")
