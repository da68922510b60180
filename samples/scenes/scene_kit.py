"""The parts the sample-scene generator builds from: vector and quaternion helpers, a fixed
pseudo-random sequence, meshes (boxes, planes, cards, surfaces of revolution, tori, arches), PNG
textures, animation keys, and `Gltf`, which collects a document and its one embedded buffer.
Python 3 standard library only; everything here is deterministic."""

import base64
import json
import math
import struct
import zlib

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
