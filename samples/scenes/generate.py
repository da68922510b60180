#!/usr/bin/env python3
"""Writes the animated sample scenes of samples/scenes/ as self-contained glTF 2.0 files.

Every asset is made here, from nothing but the Python 3 standard library: meshes, skins, the
PNG textures and the animations. Each scene is one `.gltf` with its buffer and images embedded
as base64 data URIs, and each shows something a shadow module must get right (README.md in this
folder says what). Lights use KHR_lights_punctual; their shadow settings are the engine's
`extras.shadow` (the project README's "glTF scenes" section).

Conventions are glTF's: metres, +Y up, right-handed; lights and cameras look down their node's
-Z. Every animation is one clip whose channels start and end on the same value, so the engine's
looping (clip time = t mod duration) has no seam.

The output is deterministic: no clocks, no `random` (a fixed linear congruential generator),
floats rounded before they reach the JSON. Run `python3 samples/scenes/generate.py` and commit
what changed.
"""

import base64
import json
import math
import os
import struct
import sys
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))

# glTF enums.
FLOAT, UNSIGNED_BYTE, UNSIGNED_SHORT, UNSIGNED_INT = 5126, 5121, 5123, 5125
ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER = 34962, 34963
REPEAT, LINEAR, LINEAR_MIPMAP_LINEAR, CLAMP_TO_EDGE = 10497, 9729, 9987, 33071
COMPONENTS = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT4": 16}
FORMAT = {FLOAT: "f", UNSIGNED_BYTE: "B", UNSIGNED_SHORT: "H", UNSIGNED_INT: "I"}


# ----------------------------------------------------------------------------- small maths

def r6(x):
    """A float rounded for the JSON (keeps files small and diffs stable)."""
    v = round(float(x), 6)
    return 0.0 if v == 0.0 else v


def add(a, b):
    return [a[i] + b[i] for i in range(3)]


def sub(a, b):
    return [a[i] - b[i] for i in range(3)]


def scale(a, s):
    return [a[i] * s for i in range(3)]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def normalize(a):
    n = math.sqrt(sum(c * c for c in a))
    return [c / n for c in a]


def quat_axis_angle(axis, angle):
    """Unit quaternion (x, y, z, w) turning `angle` radians about `axis`."""
    x, y, z = normalize(axis)
    s = math.sin(0.5 * angle)
    return [x * s, y * s, z * s, math.cos(0.5 * angle)]


def quat_mul(a, b):
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return [aw * bx + ax * bw + ay * bz - az * by, aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw, aw * bw - ax * bx - ay * by - az * bz]


def quat_from_basis(right, up, back):
    """Quaternion of the rotation whose columns are `right`, `up`, `back` (x, y, z axes)."""
    m00, m10, m20 = right
    m01, m11, m21 = up
    m02, m12, m22 = back
    trace = m00 + m11 + m22
    if trace > 0.0:
        s = 0.5 / math.sqrt(trace + 1.0)
        q = [(m21 - m12) * s, (m02 - m20) * s, (m10 - m01) * s, 0.25 / s]
    elif m00 > m11 and m00 > m22:
        s = 2.0 * math.sqrt(1.0 + m00 - m11 - m22)
        q = [0.25 * s, (m01 + m10) / s, (m02 + m20) / s, (m21 - m12) / s]
    elif m11 > m22:
        s = 2.0 * math.sqrt(1.0 + m11 - m00 - m22)
        q = [(m01 + m10) / s, 0.25 * s, (m12 + m21) / s, (m02 - m20) / s]
    else:
        s = 2.0 * math.sqrt(1.0 + m22 - m00 - m11)
        q = [(m02 + m20) / s, (m12 + m21) / s, 0.25 * s, (m10 - m01) / s]
    n = math.sqrt(sum(c * c for c in q))
    return [c / n for c in q]


def look_rotation(eye, target, up=(0.0, 1.0, 0.0)):
    """Rotation of a node at `eye` whose -Z points at `target` (cameras and lights)."""
    back = normalize(sub(eye, target))
    if abs(sum(back[i] * up[i] for i in range(3))) > 0.999:
        up = (0.0, 0.0, -1.0)
    right = normalize(cross(up, back))
    return quat_from_basis(right, cross(back, right), back)


class Lcg:
    """A fixed pseudo-random sequence (Numerical Recipes' LCG), the same on every Python."""

    def __init__(self, seed):
        self.state = seed & 0xFFFFFFFF

    def uniform(self, lo=0.0, hi=1.0):
        self.state = (1664525 * self.state + 1013904223) & 0xFFFFFFFF
        return lo + (hi - lo) * (self.state / 4294967296.0)


# ----------------------------------------------------------------------------- meshes
# A mesh is a dict of lists: "positions", "normals", "indices", optionally "uvs".

def merge(*parts):
    out = {"positions": [], "normals": [], "uvs": [], "indices": []}
    for p in parts:
        base = len(out["positions"])
        out["positions"] += p["positions"]
        out["normals"] += p["normals"]
        out["uvs"] += p.get("uvs") or [[0.0, 0.0]] * len(p["positions"])
        out["indices"] += [base + i for i in p["indices"]]
    return out


def transformed(mesh, offset=(0.0, 0.0, 0.0), size=(1.0, 1.0, 1.0)):
    """`mesh` scaled per axis, then moved; normals follow the inverse transpose."""
    out = dict(mesh)
    out["positions"] = [[p[i] * size[i] + offset[i] for i in range(3)] for p in mesh["positions"]]
    out["normals"] = [normalize([n[i] / size[i] for i in range(3)]) for n in mesh["normals"]]
    return out


def box(hx=0.5, hy=0.5, hz=0.5):
    """A closed box centred on the origin, flat normals, uv 0..1 per face."""
    positions, normals, uvs, indices = [], [], [], []
    for axis in range(3):
        for sign in (1.0, -1.0):
            n = [0.0, 0.0, 0.0]
            n[axis] = sign
            u_axis, v_axis = (axis + 1) % 3, (axis + 2) % 3
            h = (hx, hy, hz)
            base = len(positions)
            for du, dv in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                p = [0.0, 0.0, 0.0]
                p[axis] = sign * h[axis]
                p[u_axis] = du * h[u_axis]
                p[v_axis] = dv * h[v_axis]
                positions.append(p)
                normals.append(list(n))
                uvs.append([0.5 + 0.5 * du, 0.5 + 0.5 * dv])
            quad = [0, 1, 2, 0, 2, 3] if sign > 0 else [0, 2, 1, 0, 3, 2]
            indices += [base + i for i in quad]
    return {"positions": positions, "normals": normals, "uvs": uvs, "indices": indices}


def plane(size_x, size_z, cells=1, uv_repeat=1.0):
    """A ground plane in XZ facing +Y, `cells` x `cells` quads, uv repeating `uv_repeat` times."""
    positions, normals, uvs, indices = [], [], [], []
    for j in range(cells + 1):
        for i in range(cells + 1):
            u, v = i / cells, j / cells
            positions.append([(u - 0.5) * size_x, 0.0, (v - 0.5) * size_z])
            normals.append([0.0, 1.0, 0.0])
            uvs.append([u * uv_repeat, v * uv_repeat])
    for j in range(cells):
        for i in range(cells):
            a = j * (cells + 1) + i
            b, c, d = a + 1, a + cells + 1, a + cells + 2
            indices += [a, c, b, b, c, d]
    return {"positions": positions, "normals": normals, "uvs": uvs, "indices": indices}


def card(width, height):
    """A vertical quad in XY facing +Z, its bottom edge on y = 0, uv (0,0) at the top left."""
    w = 0.5 * width
    return {"positions": [[-w, 0.0, 0.0], [w, 0.0, 0.0], [w, height, 0.0], [-w, height, 0.0]],
            "normals": [[0.0, 0.0, 1.0]] * 4,
            "uvs": [[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]],
            "indices": [0, 1, 2, 0, 2, 3]}


def lathe(profile, segments, caps=True):
    """A surface of revolution about +Y through `profile` [(radius, y), ...] bottom to top,
    with smooth side normals and flat caps where the radius at an end is not zero."""
    positions, normals, indices = [], [], []
    rings = len(profile)
    for k, (r, y) in enumerate(profile):
        # Side normal from the profile's slope at this ring.
        r0, y0 = profile[max(k - 1, 0)]
        r1, y1 = profile[min(k + 1, rings - 1)]
        dr, dy = r1 - r0, y1 - y0
        nr, ny = dy, -dr
        length = math.hypot(nr, ny) or 1.0
        nr, ny = nr / length, ny / length
        for s in range(segments + 1):
            a = 2.0 * math.pi * s / segments
            c, sn = math.cos(a), math.sin(a)
            positions.append([r * c, y, -r * sn])
            normals.append([nr * c, ny, -nr * sn])
    for k in range(rings - 1):
        for s in range(segments):
            a = k * (segments + 1) + s
            b, c, d = a + 1, a + segments + 1, a + segments + 2
            indices += [a, b, d, a, d, c]
    mesh = {"positions": positions, "normals": normals, "indices": indices}
    if caps:
        for (r, y), up in ((profile[0], -1.0), (profile[-1], 1.0)):
            if r <= 0.0:
                continue
            base = len(mesh["positions"])
            mesh["positions"].append([0.0, y, 0.0])
            mesh["normals"].append([0.0, up, 0.0])
            for s in range(segments):
                a = 2.0 * math.pi * s / segments
                mesh["positions"].append([r * math.cos(a), y, -r * math.sin(a)])
                mesh["normals"].append([0.0, up, 0.0])
            for s in range(segments):
                i, j = base + 1 + s, base + 1 + (s + 1) % segments
                mesh["indices"] += [base, i, j] if up > 0 else [base, j, i]
    return mesh


def cylinder(radius, height, segments=16):
    """A closed cylinder standing on y = 0."""
    return lathe([(radius, 0.0), (radius, height)], segments)


def sphere(radius, segments=16, rings=10):
    profile = [(radius * math.sin(math.pi * k / rings), -radius * math.cos(math.pi * k / rings))
               for k in range(rings + 1)]
    return lathe(profile, segments, caps=False)


def torus(major, minor, segments=24, sides=10):
    """A torus about +Y."""
    positions, normals, indices = [], [], []
    for i in range(segments + 1):
        a = 2.0 * math.pi * i / segments
        ca, sa = math.cos(a), math.sin(a)
        for j in range(sides + 1):
            b = 2.0 * math.pi * j / sides
            cb, sb = math.cos(b), math.sin(b)
            positions.append([(major + minor * cb) * ca, minor * sb, -(major + minor * cb) * sa])
            normals.append([cb * ca, sb, -cb * sa])
    for i in range(segments):
        for j in range(sides):
            a = i * (sides + 1) + j
            b, c, d = a + 1, a + sides + 1, a + sides + 2
            indices += [a, c, d, a, d, b]
    return {"positions": positions, "normals": normals, "indices": indices}


def arch(inner, outer, depth, segments=12):
    """A semicircular arch in the XY plane (springing at y = 0), `depth` thick along Z: the
    intrados, the extrados, both faces and the two feet, flat normals on the flat parts."""
    parts = []
    hz = 0.5 * depth
    ring = [(math.cos(math.pi * s / segments), math.sin(math.pi * s / segments)) for s in range(segments + 1)]
    for radius, sign in ((outer, 1.0), (inner, -1.0)):  # curved faces
        positions, normals, indices = [], [], []
        for c, s in ring:
            for z in (-hz, hz):
                positions.append([radius * c, radius * s, z])
                normals.append([sign * c, sign * s, 0.0])
        for k in range(segments):
            a = 2 * k
            quad = [a, a + 2, a + 3, a, a + 3, a + 1] if sign > 0 else [a, a + 3, a + 2, a, a + 1, a + 3]
            indices += quad
        parts.append({"positions": positions, "normals": normals, "indices": indices})
    for z in (-hz, hz):  # flat faces
        positions, normals, indices = [], [], []
        for c, s in ring:
            positions += [[inner * c, inner * s, z], [outer * c, outer * s, z]]
            normals += [[0.0, 0.0, 1.0 if z > 0 else -1.0]] * 2
        for k in range(segments):
            a = 2 * k
            indices += [a, a + 1, a + 3, a, a + 3, a + 2] if z > 0 else [a, a + 3, a + 1, a, a + 2, a + 3]
        parts.append({"positions": positions, "normals": normals, "indices": indices})
    for x in (-1.0, 1.0):  # feet
        lo, hi = sorted((x * inner, x * outer))
        parts.append({"positions": [[lo, 0.0, -hz], [hi, 0.0, -hz], [hi, 0.0, hz], [lo, 0.0, hz]],
                      "normals": [[0.0, -1.0, 0.0]] * 4, "indices": [0, 1, 2, 0, 2, 3]})
    return merge(*parts)


# ----------------------------------------------------------------------------- PNG

def png(width, height, pixel, channels):
    """A PNG of 8-bit RGB (channels 3) or RGBA (4); `pixel(x, y)` gives a tuple of 0..255."""
    rows = bytearray()
    for y in range(height):
        rows.append(0)  # filter: none
        for x in range(width):
            rows += bytes(pixel(x, y))

    def chunk(tag, data):
        body = tag + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    color_type = 6 if channels == 4 else 2
    header = struct.pack(">IIBBBBB", width, height, 8, color_type, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(bytes(rows), 9)) +
            chunk(b"IEND", b""))


def checker_png(size, cells, a, b):
    """An sRGB checkerboard, `cells` squares per edge, with a thin darker grout line."""
    cell = size // cells

    def pixel(x, y):
        c = a if ((x // cell) + (y // cell)) % 2 == 0 else b
        if x % cell == 0 or y % cell == 0:
            c = tuple(int(v * 0.7) for v in c)
        return c
    return png(size, size, pixel, 3)


def lattice_png(size, bars, bar_width, color):
    """Diagonal lattice slats: opaque on the slats, alpha 0 between them; a frame round it."""
    def pixel(x, y):
        u, v = (x + 0.5) / size, (y + 0.5) / size
        d1 = ((u + v) * bars) % 1.0
        d2 = ((u - v) * bars) % 1.0
        on = min(d1, 1.0 - d1) < bar_width or min(d2, 1.0 - d2) < bar_width
        frame = min(u, v, 1.0 - u, 1.0 - v) < 0.04
        shade = 0.85 + 0.15 * math.sin(40.0 * u)  # a little wood grain
        r, g, b = (int(c * shade) for c in color)
        return (r, g, b, 255 if (on or frame) else 0)
    return png(size, size, pixel, 4)


def leaf_png(size, color):
    """A leaf in alpha: a pointed ellipse with a stem, a midrib and side veins in the colour."""
    def pixel(x, y):
        u, v = (x + 0.5) / size * 2.0 - 1.0, (y + 0.5) / size  # u across, v from tip (0) to stem (1)
        half_width = 0.8 * math.sin(math.pi * min(max((v - 0.02) / 0.83, 0.0), 1.0)) ** 0.8
        inside = abs(u) < half_width
        stem = v > 0.84 and abs(u) < 0.04
        vein = abs(u) < 0.025 or (abs(((v + 0.6 * abs(u)) * 7.0) % 1.0 - 0.5) < 0.05 and abs(u) < half_width * 0.8)
        k = 0.75 if vein else 1.0 - 0.25 * abs(u)
        r, g, b = (int(c * k) for c in color)
        return (r, g, b, 255 if (inside or stem) else 0)
    return png(size, size, pixel, 4)


# ----------------------------------------------------------------------------- glTF builder

class Gltf:
    """Collects a glTF document and its one binary buffer."""

    def __init__(self, name):
        self.name = name
        self.buffer = bytearray()
        self.doc = {"asset": {"version": "2.0", "generator": "shadow engine samples/scenes/generate.py",
                              "copyright": "Generated by the shadow engine project; its licence"},
                    "scene": 0, "scenes": [{"name": name, "nodes": []}],
                    "nodes": [], "meshes": [], "materials": [], "accessors": [], "bufferViews": [],
                    "buffers": [], "cameras": [], "animations": []}
        self.lights = []
        self.channels = []  # (node, path, times, values, interpolation)
        self.mesh_cache = {}

    # --- buffer

    def view(self, data, target=None):
        while len(self.buffer) % 4:
            self.buffer.append(0)
        view = {"buffer": 0, "byteOffset": len(self.buffer), "byteLength": len(data)}
        if target is not None:
            view["target"] = target
        self.buffer += data
        self.doc["bufferViews"].append(view)
        return len(self.doc["bufferViews"]) - 1

    def accessor(self, values, kind, component=FLOAT, target=None, bounds=False, normalized=False):
        """`values`: a flat list for SCALAR, else a list of tuples of COMPONENTS[kind]."""
        n = COMPONENTS[kind]
        flat = values if n == 1 else [c for v in values for c in v]
        data = struct.pack("<%d%s" % (len(flat), FORMAT[component]), *flat)
        acc = {"bufferView": self.view(data, target), "componentType": component,
               "count": len(values), "type": kind}
        if normalized:
            acc["normalized"] = True
        if bounds:
            rows = [[v] for v in values] if n == 1 else values
            if component == FLOAT:  # bounds of the float32 values actually stored
                rows = [struct.unpack("<%df" % n, struct.pack("<%df" % n, *row)) for row in rows]
            acc["min"] = [r6(min(r[i] for r in rows)) for i in range(n)]
            acc["max"] = [r6(max(r[i] for r in rows)) for i in range(n)]
        self.doc["accessors"].append(acc)
        return len(self.doc["accessors"]) - 1

    # --- content

    def material(self, name, color, roughness=0.7, metallic=0.0, texture=None, mask=False, double_sided=False):
        pbr = {"baseColorFactor": [r6(c) for c in color] + [1.0],
               "roughnessFactor": r6(roughness), "metallicFactor": r6(metallic)}
        if texture is not None:
            pbr["baseColorTexture"] = {"index": texture, "texCoord": 0}
        mat = {"name": name, "pbrMetallicRoughness": pbr}
        if mask:
            mat["alphaMode"] = "MASK"
            mat["alphaCutoff"] = 0.5
        if double_sided:
            mat["doubleSided"] = True
        self.doc["materials"].append(mat)
        return len(self.doc["materials"]) - 1

    def texture(self, name, png_bytes, wrap=REPEAT):
        doc = self.doc
        doc.setdefault("images", []).append(
            {"name": name, "uri": "data:image/png;base64," + base64.b64encode(png_bytes).decode("ascii")})
        doc.setdefault("samplers", []).append(
            {"magFilter": LINEAR, "minFilter": LINEAR_MIPMAP_LINEAR, "wrapS": wrap, "wrapT": wrap})
        doc.setdefault("textures", []).append(
            {"name": name, "source": len(doc["images"]) - 1, "sampler": len(doc["samplers"]) - 1})
        return len(doc["textures"]) - 1

    def primitive(self, geometry, material, uvs=False, skin_attributes=None):
        count = len(geometry["positions"])
        attributes = {
            "POSITION": self.accessor([tuple(p) for p in geometry["positions"]], "VEC3", target=ARRAY_BUFFER,
                                      bounds=True),
            "NORMAL": self.accessor([tuple(n) for n in geometry["normals"]], "VEC3", target=ARRAY_BUFFER),
        }
        if uvs:
            attributes["TEXCOORD_0"] = self.accessor([tuple(t) for t in geometry["uvs"]], "VEC2",
                                                     target=ARRAY_BUFFER)
        if skin_attributes:
            joints, weights = skin_attributes
            attributes["JOINTS_0"] = self.accessor(joints, "VEC4", UNSIGNED_BYTE, ARRAY_BUFFER)
            attributes["WEIGHTS_0"] = self.accessor(weights, "VEC4", target=ARRAY_BUFFER)
        component = UNSIGNED_SHORT if count < 65536 else UNSIGNED_INT
        indices = self.accessor(geometry["indices"], "SCALAR", component, ELEMENT_ARRAY_BUFFER)
        return {"attributes": attributes, "indices": indices, "material": material}

    def mesh(self, name, primitives):
        """`primitives`: [(geometry, material)] or [(geometry, material, uvs)]."""
        if name in self.mesh_cache:
            return self.mesh_cache[name]
        prims = [self.primitive(*p) for p in primitives]
        self.doc["meshes"].append({"name": name, "primitives": prims})
        self.mesh_cache[name] = len(self.doc["meshes"]) - 1
        return self.mesh_cache[name]

    def node(self, name, parent=None, mesh=None, t=None, r=None, s=None, extras=None, **fields):
        node = {"name": name}
        if mesh is not None:
            node["mesh"] = mesh
        if t is not None:
            node["translation"] = [r6(c) for c in t]
        if r is not None:
            node["rotation"] = [r6(c) for c in r]
        if s is not None:
            node["scale"] = [r6(c) for c in s]
        if extras is not None:
            node["extras"] = extras
        node.update(fields)
        self.doc["nodes"].append(node)
        index = len(self.doc["nodes"]) - 1
        if parent is None:
            self.doc["scenes"][0]["nodes"].append(index)
        else:
            self.doc["nodes"][parent].setdefault("children", []).append(index)
        return index

    def camera(self, name, eye, target, yfov=0.8, znear=0.1, zfar=200.0, aspect=16.0 / 9.0):
        self.doc["cameras"].append({"name": name, "type": "perspective",
                                    "perspective": {"yfov": r6(yfov), "znear": r6(znear), "zfar": r6(zfar),
                                                    "aspectRatio": r6(aspect)}})
        return self.node(name, t=eye, r=look_rotation(eye, target), camera=len(self.doc["cameras"]) - 1)

    def light(self, name, kind, color, intensity, shadow, eye=None, target=None, parent=None, range_=None,
              inner=None, outer=None, direction=None):
        """A KHR_lights_punctual light on a node of its own; `shadow` is its `extras.shadow`.
        Aimed at `target` from `eye`, or along `direction` (a sun, placed 100 m up-light)."""
        light = {"name": name, "type": kind, "color": [r6(c) for c in color], "intensity": r6(intensity),
                 "extras": {"shadow": shadow}}
        if range_ is not None:
            light["range"] = r6(range_)
        if kind == "spot":
            light["spot"] = {"innerConeAngle": r6(inner), "outerConeAngle": r6(outer)}
        self.lights.append(light)
        rotation = None
        if direction is not None:
            rotation = look_rotation((0.0, 0.0, 0.0), direction)
            eye = scale(normalize(direction), -100.0)
        elif target is not None:
            rotation = look_rotation(eye, target)
        return self.node(name, parent=parent, t=eye, r=rotation,
                         extensions={"KHR_lights_punctual": {"light": len(self.lights) - 1}})

    def animate(self, node, path, times, values, interpolation="LINEAR"):
        self.channels.append((node, path, times, values, interpolation))

    # --- output

    def finish(self):
        doc = self.doc
        if self.channels:
            samplers, channels = [], []
            time_accessors = {}
            for node, path, times, values, interpolation in self.channels:
                key = tuple(times)
                if key not in time_accessors:
                    time_accessors[key] = self.accessor(list(times), "SCALAR", bounds=True)
                kind = "VEC4" if path == "rotation" else "VEC3"
                output = self.accessor([tuple(v) for v in values], kind)
                samplers.append({"input": time_accessors[key], "output": output, "interpolation": interpolation})
                channels.append({"sampler": len(samplers) - 1, "target": {"node": node, "path": path}})
            doc["animations"].append({"name": "loop", "samplers": samplers, "channels": channels})
        if self.lights:
            doc["extensionsUsed"] = ["KHR_lights_punctual"]
            doc["extensions"] = {"KHR_lights_punctual": {"lights": self.lights}}
        doc["buffers"].append({"byteLength": len(self.buffer), "uri": "data:application/octet-stream;base64," +
                               base64.b64encode(bytes(self.buffer)).decode("ascii")})
        for key in [k for k, v in doc.items() if v == []]:
            del doc[key]
        return json.dumps(doc, indent=1, separators=(",", ": ")) + "\n"


# ----------------------------------------------------------------------------- animation keys

def loop_times(duration, keys):
    """`keys` + 1 evenly spaced times over [0, duration]; the last key repeats the first."""
    return [duration * k / keys for k in range(keys + 1)]


def spin_keys(axis, duration, turns=1, keys=8, base=None):
    """Rotation keys for `turns` whole turns about `axis` over `duration`, ending where they start."""
    keys = keys * max(turns, 1)
    values = []
    for k in range(keys + 1):
        q = quat_axis_angle(axis, 2.0 * math.pi * turns * k / keys)
        values.append(quat_mul(q, base) if base else q)
    return loop_times(duration, keys), values


def swing_keys(axis, amplitude, duration, keys=16, phase=0.0, base=None, cycles=1):
    """Pendulum-like rotation keys: amplitude * sin(2 pi cycles t / duration + phase) about `axis`."""
    values = []
    for k in range(keys + 1):
        angle = amplitude * math.sin(2.0 * math.pi * cycles * k / keys + phase)
        q = quat_axis_angle(axis, angle)
        values.append(quat_mul(base, q) if base else q)
    return loop_times(duration, keys), values


def shuttle_keys(start, end, duration, keys=16, phase=0.0):
    """Translation keys easing from `start` to `end` and back (a cosine), once per `duration`."""
    values = []
    for k in range(keys + 1):
        u = 0.5 - 0.5 * math.cos(2.0 * math.pi * k / keys + phase)
        values.append([start[i] + (end[i] - start[i]) * u for i in range(3)])
    return loop_times(duration, keys), values


def roll_keys(start_x, end_x, radius, duration, keys, base, phase=0.0):
    """Rotation keys of a wheel of `radius` on a body moving as `shuttle_keys` does along X.
    Keys close enough that each step turns less than half a turn (slerp takes the short way)."""
    values = []
    for k in range(keys + 1):
        u = 0.5 - 0.5 * math.cos(2.0 * math.pi * k / keys + phase)
        angle = -(end_x - start_x) * u / radius
        values.append(quat_mul(base, quat_axis_angle((0, 1, 0), angle)))
    return loop_times(duration, keys), values


# ----------------------------------------------------------------------------- scenes

def shadow_settings(technique, map_size=1024, **knobs):
    settings = {"technique": technique}
    if technique != "none":
        settings["mapSize"] = map_size
    settings.update({k: r6(v) if isinstance(v, float) else v for k, v in knobs.items()})
    return settings


def courtyard():
    """A courtyard at dusk: walls, an arcade of columns and arches, a rotating sculpture, a
    swinging lantern and a sliding cart under eight coloured lights and a dim moon."""
    g = Gltf("courtyard")
    stone = g.material("sandstone", (0.72, 0.52, 0.36), 0.85)
    paving = g.material("paving", (0.58, 0.47, 0.38), 0.9)
    plaster = g.material("ochre plaster", (0.80, 0.58, 0.30), 0.9)
    plaster2 = g.material("rose plaster", (0.70, 0.36, 0.32), 0.9)
    bronze = g.material("bronze", (0.80, 0.55, 0.25), 0.35, 0.9)
    teal = g.material("teal enamel", (0.10, 0.55, 0.55), 0.4)
    wood = g.material("cart wood", (0.50, 0.28, 0.14), 0.8)
    red = g.material("red paint", (0.75, 0.12, 0.10), 0.5)
    iron = g.material("iron", (0.18, 0.18, 0.20), 0.5, 0.8)
    glass = g.material("lantern glass", (1.0, 0.85, 0.55), 0.2)

    unit = box()
    ground = g.mesh("ground", [(plane(24.0, 24.0, 4), paving)])
    wall_a = g.mesh("wall ochre", [(unit, plaster)])
    wall_b = g.mesh("wall rose", [(unit, plaster2)])
    stone_box = g.mesh("stone block", [(unit, stone)])
    column = g.mesh("column", [(merge(cylinder(0.28, 3.0, 16), transformed(box(0.38, 0.15, 0.38), (0, 0.15, 0)),
                                      transformed(box(0.38, 0.12, 0.38), (0, 2.88, 0))), stone)])
    arch_mesh = g.mesh("arch", [(arch(1.12, 1.5, 0.6, 12), stone)])

    g.node("ground", mesh=ground)
    # Walls: north (back), west and east, leaving the south open to the camera.
    g.node("north wall", mesh=wall_a, t=(0, 4.0, -9.0), s=(20.0, 8.0, 0.6))
    g.node("west wall", mesh=wall_b, t=(-10.0, 3.5, -2.0), s=(0.6, 7.0, 14.0))
    g.node("east wall", mesh=wall_b, t=(10.0, 3.0, -1.0), s=(0.6, 6.0, 16.0))
    # The arcade along the west side: columns carrying arches and a beam above them.
    for k in range(5):
        z = -7.0 + 3.0 * k
        g.node("column %d" % k, mesh=column, t=(-6.0, 0.0, z))
        if k < 4:
            g.node("arch %d" % k, mesh=arch_mesh, t=(-6.0, 3.0, z + 1.5), r=quat_axis_angle((0, 1, 0), math.pi / 2))
    g.node("arcade beam", mesh=stone_box, t=(-6.0, 4.75, -1.0), s=(0.6, 0.5, 12.6))
    g.node("arcade roof", mesh=stone_box, t=(-8.0, 5.1, -1.0), s=(4.6, 0.2, 12.6))
    # Steps and benches: low casters for the ground lights.
    g.node("step", mesh=stone_box, t=(2.0, 0.15, -7.6), s=(6.0, 0.3, 2.2))
    g.node("bench west", mesh=stone_box, t=(-3.2, 0.25, 3.0), s=(0.6, 0.5, 2.2))
    g.node("bench east", mesh=stone_box, t=(7.6, 0.25, -1.5), s=(2.2, 0.5, 0.6))
    barrel = g.mesh("barrel", [(lathe([(0.3, 0.0), (0.36, 0.45), (0.3, 0.9)], 14), wood)])
    for k, (x, z) in enumerate(((8.8, 1.2), (8.9, 2.0), (8.0, 1.6))):
        g.node("barrel %d" % k, mesh=barrel, t=(x, 0.0, z))
    g.node("crate", mesh=g.mesh("crate", [(unit, teal)]), t=(8.6, 0.35, 3.2), s=(0.7, 0.7, 0.7),
           r=quat_axis_angle((0, 1, 0), 0.3))

    # The sculpture: two interlocked rings on a plinth, turning.
    g.node("plinth", mesh=stone_box, t=(1.0, 0.5, -2.0), s=(1.4, 1.0, 1.4))
    ring_a = g.mesh("ring bronze", [(torus(0.9, 0.12, 28, 10), bronze)])
    ring_b = g.mesh("ring teal", [(torus(0.75, 0.1, 28, 10), teal)])
    sculpture = g.node("sculpture", t=(1.0, 2.05, -2.0))
    ring_a_node = g.node("ring a", parent=sculpture, mesh=ring_a, r=quat_axis_angle((1, 0, 0), math.pi / 2))
    ring_b_node = g.node("ring b", parent=sculpture, mesh=ring_b, r=quat_axis_angle((0, 0, 1), math.pi / 2))
    duration = 12.0
    g.animate(sculpture, "rotation", *spin_keys((0, 1, 0), duration))
    g.animate(ring_b_node, "rotation",
              *spin_keys((1, 0, 0), duration, turns=2, base=quat_axis_angle((0, 0, 1), math.pi / 2)))
    del ring_a_node

    # The lantern: an iron arm from the east wall, a chain pivot swinging, a lamp that casts
    # nothing itself (its light sits inside it).
    g.node("lantern arm", mesh=g.mesh("iron bar", [(unit, iron)]), t=(8.9, 3.2, 1.8), s=(1.6, 0.08, 0.08))
    pivot = g.node("lantern pivot", t=(8.2, 3.2, 1.8))
    g.animate(pivot, "rotation", *swing_keys((1, 0, 0.3), 0.45, duration, keys=24, cycles=3))
    g.node("lantern chain", parent=pivot, mesh=g.mesh("iron bar", []), t=(0, -0.45, 0), s=(0.03, 0.9, 0.03))
    lamp = g.mesh("lantern", [(merge(box(0.14, 0.2, 0.14), transformed(box(0.2, 0.03, 0.2), (0, 0.22, 0))),
                               glass)])
    g.node("lantern lamp", parent=pivot, mesh=lamp, t=(0, -1.1, 0), extras={"shadow": {"cast": False}})
    g.light("lantern light", "point", (1.0, 0.62, 0.28), 8.0,
            shadow_settings("pcss", 1024, radius=0.12), eye=(0, -1.1, 0), parent=pivot, range_=14.0)

    # The cart: a body on four wheels sliding along the south side, wheels turning.
    cart = g.node("cart", t=(-2.0, 0.0, 4.2))
    cart_start, cart_end = (-2.5, 0.0, 4.2), (5.0, 0.0, 4.2)
    g.animate(cart, "translation", *shuttle_keys(cart_start, cart_end, duration, keys=96, phase=0.5 * math.pi))
    g.node("cart body", parent=cart, mesh=g.mesh("cart body", [(unit, wood)]), t=(0, 0.75, 0), s=(1.8, 0.5, 1.0))
    g.node("cart load", parent=cart, mesh=g.mesh("cart load", [(unit, red)]), t=(0.2, 1.2, 0), s=(0.9, 0.4, 0.7))
    wheel = g.mesh("wheel", [(transformed(cylinder(0.35, 0.1, 14), (0, -0.05, 0)), iron)])
    for k, (x, z) in enumerate(((-0.6, 0.55), (0.6, 0.55), (-0.6, -0.55), (0.6, -0.55))):
        hub = g.node("wheel %d" % k, parent=cart, t=(x, 0.35, z))
        # The wheels roll without slipping: turned by -distance / radius about their axle
        # (local +Y, world +Z once the cylinder is laid on its side).
        base = quat_axis_angle((1, 0, 0), math.pi / 2)
        g.animate(hub, "rotation", *roll_keys(cart_start[0], cart_end[0], 0.35, duration, keys=96, base=base,
                                                    phase=0.5 * math.pi))
        g.node("wheel %d rim" % k, parent=hub, mesh=wheel)

    # Lights: a dim moon and eight coloured lamps, mixed techniques, one without shadows.
    g.light("moon", "directional", (0.55, 0.65, 1.0), 0.08,
            shadow_settings("pcf", 2048, angularRadius=0.01, cascades=2, pcfRadius=0.06, shadowDistance=40.0),
            direction=(-0.35, -0.6, -0.5))
    # From behind the sculpture: the rings' shadow turning on the ground in front of it.
    g.light("sculpture spot", "spot", (1.0, 0.55, 0.25), 150.0, shadow_settings("pcss", 2048, radius=0.3),
            eye=(-1.5, 7.0, -7.0), target=(2.2, 0.0, 1.5), range_=30.0, inner=0.28, outer=0.42)
    # Throws the columns' shadows through the arches on the west wall.
    g.light("arcade spot", "spot", (0.35, 0.6, 1.0), 110.0, shadow_settings("pcss", 2048, radius=0.15),
            eye=(3.0, 4.5, 4.0), target=(-8.0, 1.5, -3.0), range_=30.0, inner=0.35, outer=0.55)
    # Low in front of the sculpture: its shadow, magnified, on the north wall.
    g.light("wall wash", "spot", (0.9, 0.25, 0.6), 60.0, shadow_settings("pcf", 1024, pcfRadius=0.04),
            eye=(1.0, 0.5, 2.8), target=(1.0, 3.5, -9.0), range_=25.0, inner=0.3, outer=0.45)
    g.light("step lamp", "point", (0.35, 1.0, 0.45), 5.0, shadow_settings("hard", 1024),
            eye=(4.5, 0.9, -6.2), range_=8.0)
    g.light("arcade lamp", "point", (1.0, 0.75, 0.45), 5.0, shadow_settings("pcss", 1024, radius=0.08),
            eye=(-7.8, 2.6, -2.5), range_=9.0)
    # Over the cart's path from the front: its hard shadow slides along behind it.
    g.light("cart spot", "spot", (1.0, 0.9, 0.7), 60.0, shadow_settings("hard", 1024),
            eye=(1.2, 6.0, 9.0), target=(1.2, 0.0, 3.6), range_=25.0, inner=0.45, outer=0.6)
    g.light("fill", "point", (0.4, 0.45, 1.0), 1.0, shadow_settings("none"), eye=(0.0, 4.0, 8.0), range_=20.0)

    g.camera("camera", eye=(7.0, 3.0, 9.0), target=(-0.5, 1.3, -2.5), yfov=0.9, zfar=100.0)
    return g


def sunfield():
    """A wide field under a low sun: 300 m of ground, scattered columns, boxes and box trees,
    some moving, a camera near the ground looking toward the horizon, four PCSS cascades."""
    g = Gltf("sunfield")
    grass = g.material("meadow", (0.32, 0.48, 0.16), 0.95)
    road = g.material("dust road", (0.62, 0.50, 0.36), 0.95)
    sky = g.material("sky", (0.35, 0.55, 1.0), 1.0)
    bark = g.material("bark", (0.36, 0.22, 0.12), 0.9)
    leaves = [g.material("leaves %d" % k, c, 0.8) for k, c in
              enumerate(((0.18, 0.45, 0.12), (0.28, 0.52, 0.10), (0.45, 0.55, 0.12)))]
    paints = [g.material("paint %d" % k, c, 0.6) for k, c in
              enumerate(((0.80, 0.30, 0.20), (0.85, 0.70, 0.25), (0.25, 0.45, 0.75), (0.85, 0.85, 0.80)))]
    stone = g.material("white stone", (0.85, 0.82, 0.75), 0.7)
    blade = g.material("blade", (0.90, 0.90, 0.92), 0.5)

    g.node("ground", mesh=g.mesh("ground", [(plane(300.0, 300.0, 6), grass)]))
    g.node("road", mesh=g.mesh("road", [(transformed(plane(6.0, 300.0, 1), (0, 0.02, 0)), road)]), t=(4.0, 0, 0))
    # The sky: a hemisphere seen from inside, neither casting nor receiving. Its normals lean
    # toward the sun, so that it is lit evenly, brighter toward the sun, and never black.
    sun_direction = (-1.0, -0.42, -0.55)
    to_sun = scale(normalize(sun_direction), -1.0)
    dome = lathe([(400.0 * math.cos(math.pi / 2 * k / 8), 400.0 * math.sin(math.pi / 2 * k / 8) - 20.0)
                  for k in range(9)], 32, caps=False)
    dome["normals"] = [normalize(add(scale(to_sun, 1.6), scale(n, -1.0))) for n in dome["normals"]]
    dome["indices"] = [i for t in range(0, len(dome["indices"]), 3)
                       for i in (dome["indices"][t], dome["indices"][t + 2], dome["indices"][t + 1])]
    g.node("sky", mesh=g.mesh("sky", [(dome, sky)]), extras={"shadow": {"cast": False, "receive": False}})

    unit = box()
    tree_meshes = []
    for k, leaf in enumerate(leaves):
        canopy = merge(transformed(box(), (0, 3.2, 0), (2.6, 1.6, 2.6)), transformed(box(), (0, 4.4, 0), (1.8, 1.2, 1.8)),
                       transformed(box(), (0, 5.3, 0), (1.0, 0.8, 1.0)))
        tree_meshes.append(g.mesh("tree %d" % k, [(transformed(box(), (0, 1.3, 0), (0.35, 2.6, 0.35)), bark),
                                                  (canopy, leaf)]))
    column = g.mesh("column", [(merge(cylinder(0.45, 6.0, 12), transformed(box(0.6, 0.2, 0.6), (0, 6.1, 0))),
                                stone)])
    boxes = [g.mesh("box %d" % k, [(unit, p)]) for k, p in enumerate(paints)]

    rng = Lcg(20240611)
    placed = []

    def free(x, z, clearance):
        if abs(x - 4.0) < 4.0 + clearance:  # keep the road clear
            return False
        if x * x + (z - 4.0) ** 2 < 14.0 ** 2:  # and the camera's foreground (the near group's)
            return False
        return all((x - px) ** 2 + (z - pz) ** 2 > (clearance + pr) ** 2 for px, pz, pr in placed)

    def scatter(count, clearance, near=140.0):
        out = []
        while len(out) < count:
            x, z = rng.uniform(-near, near), rng.uniform(-near, near)
            if free(x, z, clearance):
                placed.append((x, z, clearance))
                out.append((x, z))
        return out

    for k, (x, z) in enumerate(scatter(90, 2.0)):
        g.node("tree %d" % k, mesh=tree_meshes[k % 3], t=(x, 0, z), r=quat_axis_angle((0, 1, 0), rng.uniform(0, 1.5)),
               s=[rng.uniform(0.8, 1.4)] * 3)
    for k, (x, z) in enumerate(scatter(30, 1.0)):
        g.node("column %d" % k, mesh=column, t=(x, 0, z), s=(1.0, rng.uniform(0.5, 1.3), 1.0))
    for k, (x, z) in enumerate(scatter(60, 1.5)):
        w, h, d = rng.uniform(0.8, 3.0), rng.uniform(0.6, 3.5), rng.uniform(0.8, 3.0)
        g.node("box %d" % k, mesh=boxes[k % 4], t=(x, 0.5 * h, z), s=(w, h, d),
               r=quat_axis_angle((0, 1, 0), rng.uniform(0, 1.5)))

    # A near group the camera looks past: where the first cascade's resolution shows.
    for k, (x, z, h) in enumerate(((-2.5, -9.0, 2.2), (1.8, -13.0, 1.2), (-5.0, -16.0, 3.0))):
        g.node("near post %d" % k, mesh=column, t=(x, 0, z), s=(0.6, h / 6.0, 0.6))
    g.node("near crate", mesh=boxes[1], t=(-0.8, 0.4, -7.0), s=(0.8, 0.8, 0.8), r=quat_axis_angle((0, 1, 0), 0.4))

    duration = 16.0
    # Moving casters: two trucks along the road, a windmill, a swaying tree, a bobbing crate.
    truck = merge(transformed(box(), (0, 1.4, 0), (2.4, 2.2, 5.0)), transformed(box(), (0, 1.1, 3.2), (2.4, 1.6, 1.4)))
    truck_mesh = g.mesh("truck", [(truck, paints[0])])
    truck_a = g.node("truck a", mesh=truck_mesh, t=(5.5, 0, -20))
    g.animate(truck_a, "translation", *shuttle_keys((5.5, 0, -16.0), (5.5, 0, -90.0), duration, keys=24,
                                                    phase=0.5 * math.pi))
    truck_b = g.node("truck b", mesh=truck_mesh, t=(2.5, 0, -60), r=quat_axis_angle((0, 1, 0), math.pi))
    g.animate(truck_b, "translation", *shuttle_keys((2.5, 0, -110.0), (2.5, 0, -30.0), duration, keys=24))
    mill_x, mill_z = -14.0, -38.0
    g.node("windmill tower", mesh=g.mesh("tower", [(lathe([(1.6, 0.0), (1.0, 12.0)], 12), paints[3])]),
           t=(mill_x, 0, mill_z))
    rotor = g.node("windmill rotor", t=(mill_x, 11.5, mill_z + 1.3))
    g.animate(rotor, "rotation", *spin_keys((0, 0, 1), duration, turns=2))
    blades = merge(*[transformed(box(), (4.0 * math.cos(a), 4.0 * math.sin(a), 0),
                                 (abs(math.cos(a)) * 7.0 + 0.7, abs(math.sin(a)) * 7.0 + 0.7, 0.15))
                     for a in (0.0, math.pi / 2, math.pi, 3 * math.pi / 2)])
    g.node("windmill blades", parent=rotor, mesh=g.mesh("blades", [(blades, blade)]))
    sway = g.node("swaying tree", mesh=tree_meshes[1], t=(-6.0, 0, -24.0), s=(1.3, 1.3, 1.3))
    g.animate(sway, "rotation", *swing_keys((1, 0, 0.4), 0.12, duration, keys=16, cycles=4))
    crate = g.node("hopping crate", mesh=boxes[2], t=(9.5, 0.6, -15.0), s=(1.2, 1.2, 1.2))
    g.animate(crate, "translation", *shuttle_keys((9.5, 0.6, -15.0), (9.5, 2.6, -15.0), duration, keys=32))

    g.light("sun", "directional", (1.0, 0.86, 0.66), 5.0,
            shadow_settings("pcss", 2048, angularRadius=0.012, cascades=4, cascadeSplitLambda=0.8,
                            shadowDistance=160.0),
            direction=sun_direction)
    g.camera("camera", eye=(0.5, 1.7, 4.0), target=(-1.5, 1.2, -40.0), yfov=0.7, znear=0.2, zfar=600.0)
    return g


def contact():
    """Contact hardening close up: a thin pole and a leaning plank on a slowly turning
    platform under a large spot emitter (PCSS), camera close."""
    g = Gltf("contact")
    floor = g.material("terracotta floor", (0.78, 0.45, 0.30), 0.9)
    disc = g.material("teal turntable", (0.20, 0.46, 0.50), 0.7)
    pole_m = g.material("yellow pole", (0.95, 0.75, 0.15), 0.4)
    plank_m = g.material("blue plank", (0.20, 0.40, 0.80), 0.6)
    ball_m = g.material("red ball", (0.85, 0.15, 0.15), 0.3)
    cube_m = g.material("green cube", (0.25, 0.70, 0.35), 0.6)

    g.node("floor", mesh=g.mesh("floor", [(plane(40.0, 40.0, 2), floor)]))
    table = g.node("turntable", t=(0, 0, 0))
    g.animate(table, "rotation", *spin_keys((0, 1, 0), 24.0))
    g.node("disc", parent=table, mesh=g.mesh("disc", [(cylinder(1.6, 0.04, 48), disc)]))
    top = 0.04
    g.node("pole", parent=table, mesh=g.mesh("pole", [(cylinder(0.03, 1.6, 12), pole_m)]), t=(-0.45, top, 0.2))
    # The plank leans 35 degrees off the vertical, one bottom edge resting on the disc.
    lean = math.radians(35.0)
    length, thick = 1.4, 0.025
    plank_rot = quat_axis_angle((0, 0, 1), lean)
    centre = (0.35 - 0.5 * length * math.sin(lean) + 0.5 * thick * math.cos(lean),
              top + 0.5 * length * math.cos(lean) + 0.5 * thick * math.sin(lean), -0.1)
    g.node("plank", parent=table, mesh=g.mesh("plank", [(box(0.5 * thick, 0.5 * length, 0.18), plank_m)]),
           t=centre, r=plank_rot)
    g.node("ball", parent=table, mesh=g.mesh("ball", [(sphere(0.15, 24, 14), ball_m)]), t=(0.55, top + 0.15, 0.55))
    g.node("cube", parent=table, mesh=g.mesh("cube", [(box(0.12, 0.12, 0.12), cube_m)]), t=(-0.2, top + 0.12, -0.6),
           r=quat_axis_angle((0, 1, 0), 0.5))

    g.light("big softbox", "spot", (1.0, 0.88, 0.72), 60.0,
            shadow_settings("pcss", 2048, radius=0.5, blockerSamples=24, pcfSamples=32),
            eye=(1.1, 3.0, 0.5), target=(-0.2, 0.0, -0.3), range_=20.0, inner=0.8, outer=1.1)
    g.light("cool fill", "point", (0.45, 0.6, 1.0), 2.5, shadow_settings("none"), eye=(-2.5, 1.8, 2.5), range_=15.0)
    g.camera("camera", eye=(0.5, 1.7, 1.9), target=(-0.2, 0.1, -0.3), yfov=0.8, znear=0.05, zfar=30.0)
    return g


def tentacle(rings, segments, height, r_base, r_tip):
    """A tapered tube standing on y = 0 with `rings` rings and a rounded tip, and each ring's y."""
    profile = [(r_base + (r_tip - r_base) * k / (rings - 1), height * k / (rings - 1)) for k in range(rings)]
    for k in range(1, 4):  # the tip's dome, closed at its pole
        a = 0.5 * math.pi * k / 3
        profile.append((r_tip * math.cos(a) if k < 3 else 0.0, height + r_tip * math.sin(a)))
    mesh = lathe(profile, segments, caps=True)
    return mesh


def skin_weights(positions, joint_heights):
    """JOINTS_0 / WEIGHTS_0 for a vertical chain: each vertex blends the two joints whose
    segment it lies in (linear in height, smoothed), weights summing to 1."""
    joints, weights = [], []
    last = len(joint_heights) - 1
    for p in positions:
        y = p[1]
        k = 0
        while k < last and y >= joint_heights[k + 1]:
            k += 1
        if k == last:
            joints.append((last, 0, 0, 0))
            weights.append((1.0, 0.0, 0.0, 0.0))
            continue
        u = (y - joint_heights[k]) / (joint_heights[k + 1] - joint_heights[k])
        u = min(max(u, 0.0), 1.0)
        w1 = u * u * (3.0 - 2.0 * u)  # smoothstep: the bend spreads over the segment
        joints.append((k, k + 1, 0, 0))
        weights.append((1.0 - w1, w1, 0.0, 0.0))
    return joints, weights


def character():
    """Three skinned tentacles (one mesh, three skins, five joints each) bending on a stage
    under a PCSS spot and a PCF sun."""
    g = Gltf("character")
    stage = g.material("stage", (0.55, 0.50, 0.62), 0.8)
    floor = g.material("floor", (0.82, 0.72, 0.55), 0.9)
    skins_m = [g.material("tentacle %d" % k, c, 0.45) for k, c in
               enumerate(((0.85, 0.25, 0.45), (0.30, 0.65, 0.85), (0.95, 0.60, 0.15)))]
    rock = g.material("rock", (0.40, 0.45, 0.38), 0.9)

    g.node("floor", mesh=g.mesh("floor", [(plane(40.0, 40.0, 2), floor)]))
    g.node("stage", mesh=g.mesh("stage", [(cylinder(2.6, 0.15, 40), stage)]))
    g.node("rock a", mesh=g.mesh("rock", [(box(), rock)]), t=(-2.4, 0.35, -1.5), s=(0.8, 0.7, 0.9),
           r=quat_axis_angle((0.2, 1, 0.1), 0.7))
    g.node("rock b", mesh=g.mesh("rock", []), t=(2.3, 0.25, -2.2), s=(0.6, 0.5, 0.5),
           r=quat_axis_angle((0.1, 1, 0.3), 0.3))

    height, n_joints = 2.4, 5
    segment = height / (n_joints - 1)
    joint_heights = [segment * k for k in range(n_joints)]
    geometry = tentacle(rings=14, segments=16, height=height, r_base=0.22, r_tip=0.06)
    joints, weights = skin_weights(geometry["positions"], joint_heights)
    inverse_bind = g.accessor([tuple(mat4_translation(0.0, -y, 0.0)) for y in joint_heights], "MAT4")
    duration = 6.0
    for t_index, (x, z, phase, bend_axis) in enumerate(((0.0, 0.0, 0.0, (0, 0, 1)), (-1.4, 0.8, 2.1, (1, 0, 0.3)),
                                                        (1.3, 0.9, 4.2, (1, 0, -0.5)))):
        # One mesh per tentacle only for its colour: the geometry is the same.
        prim = g.primitive(geometry, skins_m[t_index], skin_attributes=(joints, weights))
        g.doc["meshes"].append({"name": "tentacle %d" % t_index, "primitives": [prim]})
        mesh = len(g.doc["meshes"]) - 1
        base_y = 0.15
        chain = []
        parent = None
        for k in range(n_joints):
            t = (x, base_y, z) if k == 0 else (0.0, segment, 0.0)
            chain.append(g.node("tentacle %d joint %d" % (t_index, k), parent=parent, t=t))
            parent = chain[-1]
        # The skinned mesh node sits where the root joint stands, so a loader without skinning
        # still draws the tentacle upright in its place (glTF ignores this node's transform when
        # skinning: the joints place the mesh).
        g.doc.setdefault("skins", []).append({"name": "tentacle %d skin" % t_index, "joints": chain,
                                              "skeleton": chain[0], "inverseBindMatrices": inverse_bind})
        g.node("tentacle %d" % t_index, mesh=mesh, skin=len(g.doc["skins"]) - 1, t=(x, base_y, z))
        # Bend: every joint turns the same way, the tip joints more, as a wave up the chain.
        for k in range(1, n_joints):
            amplitude = 0.25 + 0.08 * k
            g.animate(chain[k], "rotation",
                      *swing_keys(bend_axis, amplitude, duration, keys=24, phase=phase - 0.7 * k))
        g.animate(chain[0], "rotation", *spin_keys((0, 1, 0), duration, keys=8))

    g.light("sun", "directional", (1.0, 0.92, 0.80), 2.5,
            shadow_settings("pcf", 2048, angularRadius=0.01, cascades=2, pcfRadius=0.04, shadowDistance=30.0),
            direction=(0.75, -0.8, -0.45))
    g.light("stage spot", "spot", (1.0, 0.55, 0.85), 120.0, shadow_settings("pcss", 2048, radius=0.2),
            eye=(-3.0, 5.0, 3.0), target=(0.0, 0.8, 0.0), range_=25.0, inner=0.35, outer=0.55)
    g.camera("camera", eye=(2.4, 3.4, 5.2), target=(0.2, 0.6, -0.6), yfov=0.8, zfar=60.0)
    return g


def mat4_translation(x, y, z):
    """Column-major 4x4 translation, as glTF stores matrices."""
    return [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, x, y, z, 1.0]


def fence():
    """Alpha-tested casters: lattice fence panels and leaf cards (MASK, cutoff 0.5, a PNG's
    alpha) swaying over a checkered ground, under a PCSS sun and a PCF spot."""
    g = Gltf("fence")
    ground_tex = g.texture("checker", checker_png(128, 8, (196, 164, 120), (120, 150, 96)))
    lattice_tex = g.texture("lattice", lattice_png(128, 4, 0.06, (235, 225, 205)))
    leaf_tex = g.texture("leaf", leaf_png(64, (215, 250, 190)), wrap=CLAMP_TO_EDGE)
    # The factors multiply the textures; alone (a loader without textures) they are the colours.
    ground = g.material("checker ground", (0.78, 0.68, 0.52), 0.9, texture=ground_tex)
    lattice = g.material("lattice", (0.85, 0.32, 0.22), 0.7, texture=lattice_tex, mask=True, double_sided=True)
    leaf = g.material("leaf", (0.40, 0.78, 0.25), 0.6, texture=leaf_tex, mask=True, double_sided=True)
    post = g.material("post", (0.45, 0.28, 0.16), 0.8)
    branch = g.material("branch", (0.35, 0.22, 0.12), 0.9)
    pot = g.material("pot", (0.75, 0.35, 0.20), 0.7)
    hedge = g.material("hedge", (0.22, 0.45, 0.20), 0.9)

    g.node("ground", mesh=g.mesh("ground", [(plane(20.0, 20.0, 2, uv_repeat=5.0), ground, True)]))
    # A hedge behind the fence, to catch the spot's lattice shadows.
    g.node("hedge", mesh=g.mesh("hedge", [(box(), hedge)]), t=(0.0, 1.6, -3.2), s=(12.0, 3.2, 1.0))
    panel = g.mesh("lattice panel", [(card(1.8, 1.5), lattice, True)])
    post_mesh = g.mesh("post", [(box(), post)])
    duration = 8.0
    for k in range(4):
        x = -2.7 + 1.9 * k
        g.node("post %d" % k, mesh=post_mesh, t=(x - 0.95, 0.85, -0.5), s=(0.1, 1.7, 0.1))
        hinge = g.node("panel %d hinge" % k, t=(x, 0.1, -0.5))
        g.animate(hinge, "rotation", *swing_keys((1, 0, 0), 0.07 + 0.02 * k, duration, keys=16, phase=0.9 * k,
                                                 cycles=2))
        g.node("panel %d" % k, parent=hinge, mesh=panel)
    g.node("post 4", mesh=post_mesh, t=(-2.7 + 1.9 * 4 - 0.95, 0.85, -0.5), s=(0.1, 1.7, 0.1))

    # A branch over the front with leaf cards hanging from it, each on its own stalk swaying.
    g.node("planter", mesh=g.mesh("planter", [(lathe([(0.3, 0.0), (0.4, 0.5)], 16), pot)]), t=(2.2, 0, 1.3))
    g.node("stem", mesh=g.mesh("stem", [(cylinder(0.04, 1.6, 8), branch)]), t=(2.2, 0.4, 1.3))
    bough = g.node("bough", mesh=g.mesh("bough", [(cylinder(0.03, 2.6, 8), branch)]), t=(2.2, 1.95, 1.3),
                   r=quat_axis_angle((0, 0, 1), math.radians(75.0)))
    g.animate(bough, "rotation", *swing_keys((1, 0, 0), 0.08, duration, keys=16,
                                             base=quat_axis_angle((0, 0, 1), math.radians(75.0))))
    leaf_mesh = g.mesh("leaf card", [(card(0.5, 0.5), leaf, True)])
    rng = Lcg(7)
    for k in range(9):
        along = 0.25 + 0.26 * k
        # Undo the bough's tilt, turn the card about the vertical, hang it upside down.
        yaw = rng.uniform(-1.0, 1.0)
        hang = quat_mul(quat_axis_angle((0, 1, 0), yaw), quat_axis_angle((1, 0, 0), math.pi + rng.uniform(-0.6, 0.6)))
        base = quat_mul(quat_axis_angle((0, 0, 1), math.radians(-75.0)), hang)
        stalk = g.node("leaf %d stalk" % k, parent=bough, t=(0.0, along, 0.0), r=base)
        g.animate(stalk, "rotation", *swing_keys((1, 0, 0), 0.25, duration, keys=16, phase=1.3 * k, cycles=2,
                                                 base=base))
        g.node("leaf %d" % k, parent=stalk, mesh=leaf_mesh)

    g.light("sun", "directional", (1.0, 0.9, 0.75), 4.0,
            shadow_settings("pcss", 2048, angularRadius=0.015, cascades=2, shadowDistance=25.0),
            direction=(-0.45, -0.8, 0.55))
    g.light("spot", "spot", (0.75, 0.85, 1.0), 80.0, shadow_settings("pcf", 2048, pcfRadius=0.03),
            eye=(-3.5, 3.2, 4.0), target=(0.3, 0.8, -1.5), range_=25.0, inner=0.4, outer=0.6)
    g.camera("camera", eye=(1.2, 1.7, 6.0), target=(0.2, 1.0, -0.5), yfov=0.8, zfar=60.0)
    return g


SCENES = {"courtyard": courtyard, "sunfield": sunfield, "contact": contact, "character": character, "fence": fence}


def main(argv):
    names = argv[1:] or list(SCENES)
    for name in names:
        if name not in SCENES:
            sys.exit("unknown scene %r (expected one of %s)" % (name, ", ".join(SCENES)))
        text = SCENES[name]().finish()
        path = os.path.join(HERE, name + ".gltf")
        with open(path, "w", encoding="ascii", newline="\n") as f:
            f.write(text)
        print("%s: %d bytes" % (os.path.relpath(path), len(text)))


if __name__ == "__main__":
    main(sys.argv)
