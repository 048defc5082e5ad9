"""A small demo glTF binary (.glb), written with the standard library only, for the examples when no model is given.

The node "model" is an asymmetric stack of three coloured boxes (an L-shape with a tower), so that a turntable's
rotation and a moved node are plain to see; it stands on a grey plinth, the node "floor", wider than the model can
reach when turned, so the scene's bounds (and with them a display's "auto" camera placement) stay put while the
model turns; a directional light "sun" (KHR_lights_punctual) shades the faces. Units: the model is about 1 wide,
centred on the origin, standing on y = -0.5.
"""

import json
import struct

# (centre, size, linear RGB) of each box of the model; each box is one primitive with its own material.
BOXES = [
    ((0.0, -0.35, 0.0), (1.0, 0.3, 0.5), (0.80, 0.18, 0.10)),
    ((0.35, 0.05, 0.0), (0.3, 0.5, 0.5), (0.12, 0.55, 0.20)),
    ((-0.3, -0.05, 0.15), (0.25, 0.3, 0.2), (0.15, 0.30, 0.85)),
]
FLOOR = ((0.0, -0.54, 0.0), (2.0, 0.08, 1.4), (0.45, 0.45, 0.45))

# The 6 faces of a unit box: normal and the two in-face axes (counter-clockwise seen from outside).
_FACES = [((1, 0, 0), (0, 0, -1), (0, 1, 0)), ((-1, 0, 0), (0, 0, 1), (0, 1, 0)),
          ((0, 1, 0), (1, 0, 0), (0, 0, -1)), ((0, -1, 0), (1, 0, 0), (0, 0, 1)),
          ((0, 0, 1), (1, 0, 0), (0, 1, 0)), ((0, 0, -1), (-1, 0, 0), (0, 1, 0))]


def _box(centre, size):
    """24 positions and normals (4 per face) and 36 indices of an axis-aligned box."""
    positions, normals, indices = [], [], []
    for n, u, v in _FACES:
        base = len(positions)
        for su, sv in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
            positions.append(tuple(centre[i] + 0.5 * size[i] * (n[i] + su * u[i] + sv * v[i]) for i in range(3)))
            normals.append(n)
        indices += [base, base + 1, base + 2, base, base + 2, base + 3]
    return positions, normals, indices


def _pad4(data, fill=b"\0"):
    return data + fill * (-len(data) % 4)


def demo_glb():
    """The bytes of the demo model as a .glb file."""
    binary = b""
    accessors, views, primitives, materials = [], [], [], []

    def add_view(data, target):
        nonlocal binary
        views.append({"buffer": 0, "byteOffset": len(binary), "byteLength": len(data), "target": target})
        binary = _pad4(binary + data)
        return len(views) - 1

    for index, (centre, size, colour) in enumerate(BOXES + [FLOOR]):
        positions, normals, indices = _box(centre, size)
        flat = [c for p in positions for c in p]
        accessors.append({"bufferView": add_view(struct.pack(f"<{len(flat)}f", *flat), 34962),
                          "componentType": 5126, "count": len(positions), "type": "VEC3",
                          "min": [min(p[i] for p in positions) for i in range(3)],
                          "max": [max(p[i] for p in positions) for i in range(3)]})
        flat = [float(c) for n in normals for c in n]
        accessors.append({"bufferView": add_view(struct.pack(f"<{len(flat)}f", *flat), 34962),
                          "componentType": 5126, "count": len(normals), "type": "VEC3"})
        accessors.append({"bufferView": add_view(struct.pack(f"<{len(indices)}H", *indices), 34963),
                          "componentType": 5123, "count": len(indices), "type": "SCALAR"})
        primitives.append({"attributes": {"POSITION": len(accessors) - 3, "NORMAL": len(accessors) - 2},
                           "indices": len(accessors) - 1, "material": index})
        materials.append({"name": f"box{index}", "pbrMetallicRoughness": {
            "baseColorFactor": list(colour) + [1.0], "metallicFactor": 0.0, "roughnessFactor": 0.9}})
    gltf = {
        "asset": {"version": "2.0", "generator": "holotrace_client examples/demo_model.py"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"type": "directional", "color": [1.0, 0.95, 0.9], "intensity": 3.0}]}},
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2]}],
        "nodes": [{"name": "model", "mesh": 0}, {"name": "floor", "mesh": 1},
                  # The sun shines along its -z axis: rotated to come from the upper left front.
                  {"name": "sun", "rotation": [-0.3535534, -0.3535534, 0.0, 0.8660254],
                   "extensions": {"KHR_lights_punctual": {"light": 0}}}],
        "meshes": [{"name": "stack", "primitives": primitives[:len(BOXES)]},
                   {"name": "plinth", "primitives": primitives[len(BOXES):]}],
        "materials": materials,
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(binary)}],
    }
    text = _pad4(json.dumps(gltf, separators=(",", ":")).encode(), b" ")
    chunks = (struct.pack("<I4s", len(text), b"JSON") + text + struct.pack("<I4s", len(binary), b"BIN\0") + binary)
    return struct.pack("<4sII", b"glTF", 2, 12 + len(chunks)) + chunks


if __name__ == "__main__":
    import sys
    path = sys.argv[1] if len(sys.argv) > 1 else "demo_model.glb"
    with open(path, "wb") as f:
        f.write(demo_glb())
    print(path)
