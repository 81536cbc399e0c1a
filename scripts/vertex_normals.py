#!/usr/bin/env python3
"""Takes the vertex normals out of a glTF (JSON, buffers as data URIs or files beside it) for the
RTL surface bench's geometric-normal cases (tests/test_rtl.sh, rtl/rgs_surface.sv): no scene of the
repository lacks them, so `saarcor gen cornell -o IN` and this give one.
  drop   every primitive without its NORMAL attribute: the objects have no vertex normals, the
         surface takes the triangle's geometric normal at once
  zero   the first mesh's normals all zero: decoded as missing, their interpolation has a zero
         length, and the surface takes the geometric normal after that test

usage: vertex_normals.py IN.gltf OUT.gltf drop|zero
"""
import base64
import json
import os
import sys


def main():
    if len(sys.argv) != 4 or sys.argv[3] not in ("drop", "zero"):
        sys.exit(__doc__)
    with open(sys.argv[1]) as f:
        doc = json.load(f)
    prims = [p for m in doc.get("meshes", []) for p in m["primitives"] if "NORMAL" in p["attributes"]]
    if not prims:
        sys.exit(f"vertex_normals.py: {sys.argv[1]} has no vertex normals")
    if sys.argv[3] == "drop":
        for p in prims:
            del p["attributes"]["NORMAL"]
    else:
        here = os.path.dirname(sys.argv[1])
        data = []
        for b in doc["buffers"]:
            uri = b["uri"]
            if uri.startswith("data:"):
                data.append(bytearray(base64.b64decode(uri.split(",", 1)[1])))
            else:
                with open(os.path.join(here, uri), "rb") as f:
                    data.append(bytearray(f.read()))
        for p in doc["meshes"][0]["primitives"]:
            a = doc["accessors"][p["attributes"]["NORMAL"]]
            v = doc["bufferViews"][a["bufferView"]]
            at = v.get("byteOffset", 0) + a.get("byteOffset", 0)
            data[v["buffer"]][at:at + 12 * a["count"]] = bytes(12 * a["count"])
        for b, d in zip(doc["buffers"], data):
            b["uri"] = "data:application/octet-stream;base64," + base64.b64encode(bytes(d)).decode()
    with open(sys.argv[2], "w") as f:
        json.dump(doc, f)


if __name__ == "__main__":
    main()
