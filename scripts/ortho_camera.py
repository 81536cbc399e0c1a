#!/usr/bin/env python3
"""Makes the first camera of a glTF (JSON) file orthographic, for the RTL benches' orthographic
frame (make rtl-test, tests/test_rtl.sh: the RGS's ray generation, rtl/rgs_raygen.sv): no scene of
the repository has an orthographic camera, so `saarcor gen cornell -o IN` and this give one.

usage: ortho_camera.py IN.gltf OUT.gltf [XMAG [YMAG]]   (half extents, default 1.2 1.2)
"""
import json
import sys


def main():
    if len(sys.argv) not in (3, 4, 5):
        sys.exit(__doc__)
    xmag = float(sys.argv[3]) if len(sys.argv) > 3 else 1.2
    ymag = float(sys.argv[4]) if len(sys.argv) > 4 else xmag
    with open(sys.argv[1]) as f:
        doc = json.load(f)
    if not doc.get("cameras"):
        sys.exit(f"ortho_camera.py: {sys.argv[1]} has no camera")
    doc["cameras"][0] = {"type": "orthographic",
                         "orthographic": {"xmag": xmag, "ymag": ymag, "znear": 0.1, "zfar": 100.0}}
    with open(sys.argv[2], "w") as f:
        json.dump(doc, f)


if __name__ == "__main__":
    main()
