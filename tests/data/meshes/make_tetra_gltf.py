#!/usr/bin/env python3
# Writes tetra.gltf: a regular tetrahedron (corners at (+-1, +-1, +-1) with an even number of
# minus signs), faces counter-clockwise seen from outside, one texture coordinate per corner, its
# buffer embedded as base64, under a node that scales by 2 and moves by +1 along z (so the import's
# flattening of the node hierarchy shows). Run once; the file is checked in.
import base64, json, struct

positions = [(1, 1, 1), (1, -1, -1), (-1, 1, -1), (-1, -1, 1)]
uvs = [(0, 0), (1, 0), (0, 1), (1, 1)]
triangles = [(0, 1, 2), (0, 3, 1), (0, 2, 3), (1, 3, 2)]

index_bytes = b"".join(struct.pack("<3H", *t) for t in triangles)  # 24 bytes, 4-aligned
position_bytes = b"".join(struct.pack("<3f", *p) for p in positions)
uv_bytes = b"".join(struct.pack("<2f", *t) for t in uvs)
buffer = index_bytes + position_bytes + uv_bytes

gltf = {
    "asset": {"version": "2.0", "generator": "tests/data/meshes/make_tetra_gltf.py"},
    "scene": 0,
    "scenes": [{"nodes": [0]}],
    "nodes": [{"mesh": 0, "scale": [2, 2, 2], "translation": [0, 0, 1]}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 1, "TEXCOORD_0": 2}, "indices": 0}]}],
    "buffers": [{"byteLength": len(buffer),
                 "uri": "data:application/octet-stream;base64," + base64.b64encode(buffer).decode()}],
    "bufferViews": [
        {"buffer": 0, "byteOffset": 0, "byteLength": len(index_bytes), "target": 34963},
        {"buffer": 0, "byteOffset": len(index_bytes), "byteLength": len(position_bytes), "target": 34962},
        {"buffer": 0, "byteOffset": len(index_bytes) + len(position_bytes), "byteLength": len(uv_bytes),
         "target": 34962},
    ],
    "accessors": [
        {"bufferView": 0, "componentType": 5123, "count": 12, "type": "SCALAR"},
        {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, -1, -1], "max": [1, 1, 1]},
        {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
    ],
}
with open("tetra.gltf", "w") as f:
    json.dump(gltf, f, indent=1)
    f.write("\n")
