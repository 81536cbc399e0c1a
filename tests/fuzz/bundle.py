#!/usr/bin/env python3
"""Turns a .gltf with embedded data: URIs into a fuzz_gltf bundle with external files: the JSON
with every buffer and image URI replaced by a file name, followed by each file as
"\\n#FILE NAME\\n" + its bytes (tests/fuzz/fuzz_gltf.c). Usage: bundle.py IN.gltf OUT"""
import base64
import json
import sys

doc = json.load(open(sys.argv[1]))
files = []
for kind, ext in (("buffers", "bin"), ("images", "png")):
    for i, item in enumerate(doc.get(kind, [])):
        uri = item.get("uri", "")
        if uri.startswith("data:") and ";base64," in uri:
            name = f"{kind[:-1]}{i}.{ext}"
            files.append((name, base64.b64decode(uri.split(";base64,", 1)[1])))
            item["uri"] = name
with open(sys.argv[2], "wb") as out:
    out.write(json.dumps(doc).encode())
    for name, data in files:
        out.write(b"\n#FILE " + name.encode() + b"\n" + data)
