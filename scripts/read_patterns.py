#!/usr/bin/env python3
"""Reads a pattern's DXF and SVG back with other people's readers, for the test that checks
them (tests/suite/patterns.rs): ezdxf for the DXF (each INSERT's block exploded into world
coordinates by ezdxf itself), Python's XML parser for the SVG. Prints JSON:
  {"dxf": {"units": N, "pieces": {BLOCK: {"cut": [[x, y], ...], "name": TEXT, "grain": [[x, y], [x, y]], "notches": K}}},
   "svg": {"width": W, "height": H, "view_box": [..], "pieces": {ID: [[x, y], ...]}}}
    python3 scripts/read_patterns.py PATTERNS.dxf PATTERNS.svg
"""
import json
import re
import sys
import xml.etree.ElementTree as ET

import ezdxf


def read_dxf(path):
    doc = ezdxf.readfile(path)
    out = {"units": doc.header.get("$INSUNITS", 0), "pieces": {}}
    for insert in doc.modelspace().query("INSERT"):
        piece = {"cut": [], "name": "", "grain": [], "notches": 0}
        for e in insert.virtual_entities():
            layer, kind = e.dxf.layer, e.dxftype()
            if kind == "POLYLINE" and layer == "1":
                piece["cut"] = [[v.dxf.location.x, v.dxf.location.y] for v in e.vertices]
                piece["closed"] = e.is_closed
            elif kind == "TEXT":
                piece["name"] = e.dxf.text
            elif kind == "LINE" and layer == "7":
                piece["grain"] = [[e.dxf.start.x, e.dxf.start.y], [e.dxf.end.x, e.dxf.end.y]]
            elif kind == "LINE" and layer == "4":
                piece["notches"] += 1
        out["pieces"][insert.dxf.name] = piece
    return out


def read_svg(path):
    ns = {"s": "http://www.w3.org/2000/svg"}
    root = ET.parse(path).getroot()
    out = {"width": root.get("width"), "height": root.get("height"),
           "view_box": [float(x) for x in root.get("viewBox").split()], "pieces": {}}
    for g in root.findall("s:g", ns):
        d = g.find("s:path", ns).get("d")
        numbers = [float(x) for x in re.findall(r"-?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?", d)]
        out["pieces"][g.get("id")] = [numbers[i:i + 2] for i in range(0, len(numbers), 2)]
    return out


if __name__ == "__main__":
    print(json.dumps({"dxf": read_dxf(sys.argv[1]), "svg": read_svg(sys.argv[2])}))
