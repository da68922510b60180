#!/usr/bin/env python3
"""Writes a glTF scene of a ground plane and a box lit by the lights given, for the compile-time
benchmark: each light as TYPE:TECHNIQUE[:KERNEL[:CASCADES]], or COUNTxTYPE:TECHNIQUE... for
several alike. Lights stand on a ring above the box, each aimed at it, with a small emitter.

    python3 benchmarks/light_scenes.py [--instances N] OUT.gltf SPEC [SPEC ...]

--instances N adds N more copies of the ground and box, at a fifth of the size, on a grid 3 m
apart behind the camera: casters every light reaches but that neither the view nor its shadow
rays come near (the distance-field technique's cost test).
"""
import base64
import json
import math
import struct
import sys


def look_rotation(eye, target):
    """Quaternion (x, y, z, w) turning -Z towards target - eye."""
    f = [t - e for t, e in zip(target, eye)]
    length = math.sqrt(sum(x * x for x in f))
    f = [x / length for x in f]
    axis = [f[1], -f[0], 0.0]  # (0, 0, -1) x f
    w = 1.0 - f[2]
    if w < 1e-9:
        return [1.0, 0.0, 0.0, 0.0]
    q = axis + [w]
    n = math.sqrt(sum(x * x for x in q))
    return [x / n for x in q]


def geometry():
    positions, normals, indices = [], [], []

    def quad(corners, normal):
        base = len(positions)
        positions.extend(corners)
        normals.extend([normal] * 4)
        indices.extend([base, base + 1, base + 2, base, base + 2, base + 3])

    quad([(-6, 0, -6), (-6, 0, 6), (6, 0, 6), (6, 0, -6)], (0, 1, 0))
    h, y = 0.5, 1.0
    for axis in range(3):
        for sign in (-1, 1):
            n = [0, 0, 0]
            n[axis] = sign
            u = [0, 0, 0]
            v = [0, 0, 0]
            u[(axis + 1) % 3] = h
            v[(axis + 2) % 3] = h
            if sign < 0:
                u, v = v, u
            c = [0, y, 0]
            c[axis] += sign * h
            quad([tuple(c[i] + su * u[i] + sv * v[i] for i in range(3))
                  for su, sv in ((-1, -1), (1, -1), (1, 1), (-1, 1))], tuple(n))
    return positions, normals, indices


def main():
    if len(sys.argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    args = sys.argv[1:]
    instances = 0
    if args[0] == "--instances":
        instances, args = int(args[1]), args[2:]
    out, specs = args[0], []
    for spec in args[1:]:
        count = 1
        if "x" in spec.split(":")[0]:
            n, spec = spec.split("x", 1)
            count = int(n)
        specs.extend([spec] * count)
    positions, normals, indices = geometry()
    data = b"".join(struct.pack("<3f", *p) for p in positions)
    data += b"".join(struct.pack("<3f", *n) for n in normals)
    data += b"".join(struct.pack("<I", i) for i in indices)
    vertices = len(positions)
    lights, nodes = [], [{"mesh": 0}, {"camera": 0, "translation": [0, 4, 8],
                                        "rotation": look_rotation([0, 4, 8], [0, 0, 0])}]
    for k, spec in enumerate(specs):
        parts = spec.split(":")
        kind, technique = parts[0], parts[1]
        shadow = {"technique": technique, "mapSize": 256}
        if len(parts) > 2:
            shadow["kernel"] = parts[2]
        light = {"type": kind, "intensity": 2.0 if kind == "directional" else 40.0}
        if kind == "directional":
            shadow["angularRadius"] = 0.02
            if len(parts) > 3:
                shadow["cascades"] = int(parts[3])
        else:
            shadow["radius"] = 0.1
        if kind == "spot":
            light["spot"] = {"outerConeAngle": 0.8}
        light["extras"] = {"shadow": shadow}
        lights.append(light)
        angle = 2 * math.pi * k / len(specs)
        eye = [3 * math.cos(angle), 5.0, 3 * math.sin(angle)]
        nodes.append({"translation": eye, "rotation": look_rotation(eye, [0, 0, 0]),
                      "extensions": {"KHR_lights_punctual": {"light": k}}})
    for k in range(instances):
        x, z = 3.0 * (k % 20 - 9.5), 12.0 + 3.0 * (k // 20)
        nodes.append({"mesh": 0, "translation": [x, 0.0, z], "scale": [0.2, 0.2, 0.2]})
    gltf = {
        "asset": {"version": "2.0"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "buffers": [{"byteLength": len(data),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 12 * vertices},
                        {"buffer": 0, "byteOffset": 12 * vertices, "byteLength": 12 * vertices},
                        {"buffer": 0, "byteOffset": 24 * vertices, "byteLength": 4 * len(indices)}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": vertices, "type": "VEC3",
                       "min": [min(p[i] for p in positions) for i in range(3)],
                       "max": [max(p[i] for p in positions) for i in range(3)]},
                      {"bufferView": 1, "componentType": 5126, "count": vertices, "type": "VEC3"},
                      {"bufferView": 2, "componentType": 5125, "count": len(indices), "type": "SCALAR"}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2}]}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.9, "znear": 0.1, "zfar": 100.0}}],
        "nodes": nodes,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "scene": 0,
        "extensions": {"KHR_lights_punctual": {"lights": lights}},
    }
    with open(out, "w") as f:
        json.dump(gltf, f)
    return 0


if __name__ == "__main__":
    sys.exit(main())
