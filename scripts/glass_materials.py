#!/usr/bin/env python3
"""Makes every material of a glTF (JSON) file a smooth dielectric and every other one also
transmissive (KHR_materials_transmission), for the RTL bench of the RGS's block control (make
rtl-test, tests/test_rtl.sh: rtl/rgs_ctrl.sv): a packet whose rays spawn both a reflection and a
transmission task pushes the transmission task under the reflection task, the one case that
writes rgs_ctrl's stack memory and later pops it; the repository's scenes do that for a few blocks
at most (the room's vase), so `saarcor gen cornell -o IN` and this give it on most blocks.

usage: glass_materials.py IN.gltf OUT.gltf
"""
import json
import sys

EXT = "KHR_materials_transmission"


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    with open(sys.argv[1]) as f:
        doc = json.load(f)
    if not doc.get("materials"):
        sys.exit(f"glass_materials.py: {sys.argv[1]} has no material")
    for i, m in enumerate(doc["materials"]):
        pbr = m.setdefault("pbrMetallicRoughness", {})
        pbr["roughnessFactor"] = 0.0  # gloss 1: kr 0.04, a reflection child on every hit
        pbr["metallicFactor"] = 0.0
        if i % 2 == 0:  # and kt 0.96 (half the materials: the other half keep the packets' shading mixed)
            m.setdefault("extensions", {})[EXT] = {"transmissionFactor": 1.0}
    if EXT not in doc.setdefault("extensionsUsed", []):
        doc["extensionsUsed"].append(EXT)
    with open(sys.argv[2], "w") as f:
        json.dump(doc, f)


if __name__ == "__main__":
    main()
