#!/usr/bin/env python3
"""Helper of benchmarks/run_real_assets.sh: wraps a third-party .glb into a scene the shadow
techniques can be measured on, and turns the measurements into a Markdown table.

    python3 benchmarks/real_assets.py wrap IN.glb OUT.gltf [--clip NAME] [--ground-casts]
    python3 benchmarks/real_assets.py table WORK ASSET [ASSET ...]

wrap: writes OUT.gltf (JSON) and OUT.bin next to it (the GLB's binary chunk, images in buffer
views included, with the added geometry appended) and prints a JSON summary (triangles, bounds,
animation time) on stdout. Added to the asset, whose own nodes stay as they are:
  - a ground quad 4x the model's size, just below its bounds (receives, does not cast, as game
    grounds often do not; --ground-casts makes it cast, so that it is in the shadow maps);
  - a directional sun (KHR_lights_punctual, extras.shadow: PCSS, 2048 map, angularRadius
    0.02 rad) tilted 45 degrees from vertical;
  - a camera framing the model and its shadow on the ground.
A model less high than 1 % of its size (a plane) is not wrapped: exit code 3.
The camera, sun and ground are the scene's first roots, so they are camera 0 and light 0. The
bounds are those of the posed model at the chosen time: mesh nodes' POSITION min/max corners
through their world transforms; skinned meshes' vertices skinned on the CPU. Everything is
placed relative to the bounds (the size S is their largest edge), so a model at centimetre
scale gets the same framing as one at metre scale; the sun's shadow settings are the engine's
defaults, whose lengths follow the scene (texel footprints, field voxels). An asset with several
animation clips keeps one (--clip NAME, else the first whose name says walk/move/run, else the
longest): the engine plays every clip of a file at once, the last one's channels winning. The
time is the middle of the clip.

table: reads WORK/ASSET/{status,info.json,techniques,TECHNIQUE/stats.json,TECHNIQUE.json}
(status "ok", or why the asset was skipped or failed) and prints the Markdown table and, after it, one line per result that looks
wrong (no shadow in view, a black image, light in the umbra, false shadow).
"""
import json
import math
import os
import struct
import sys
import zlib

# --- the wrapper scene's constants: every length is a multiple of the model's size S ----------
GROUND_HALF = 2.0        # ground half-edge / S (a 4 S square)
GROUND_GAP = 1e-3        # ground below the bounds' bottom / S
FLAT = 0.01              # a model less high than this / S is not wrapped (exit code 3)
SUN_TILT = math.radians(45.0)   # from vertical
SUN_AZIMUTH = math.radians(-30.0)  # the shadow falls towards +X, a little towards -Z
SUN_ANGULAR_RADIUS = 0.02  # rad
CAMERA_YFOV = math.radians(40.0)
CAMERA_ELEVATION = math.radians(30.0)
CAMERA_AZIMUTH = math.radians(20.0)  # from +Z (the front of most characters) towards +X
ASPECT = 4.0 / 3.0

COMPONENT = {5120: "b", 5121: "B", 5122: "h", 5123: "H", 5125: "I", 5126: "f"}
COUNT = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT2": 4, "MAT3": 9, "MAT4": 16}
NORMALIZE = {5120: 127.0, 5121: 255.0, 5122: 32767.0, 5123: 65535.0}


def fail(message):
    print(f"real_assets.py: {message}", file=sys.stderr)
    sys.exit(2)


# --- GLB and accessors -------------------------------------------------------------------------
def read_glb(path):
    data = open(path, "rb").read()
    if len(data) < 20 or data[:4] != b"glTF":
        fail(f"{path}: not a binary glTF file")
    _, version, length = struct.unpack_from("<4sII", data, 0)
    if version != 2:
        fail(f"{path}: glTF version {version}, not 2")
    gltf, binary, offset = None, b"", 12
    while offset + 8 <= min(length, len(data)):
        chunk_length, chunk_type = struct.unpack_from("<II", data, offset)
        chunk = data[offset + 8:offset + 8 + chunk_length]
        if chunk_type == 0x4E4F534A:
            gltf = json.loads(chunk.decode("utf-8"))
        elif chunk_type == 0x004E4942 and not binary:
            binary = bytes(chunk)
        offset += 8 + chunk_length + (-chunk_length % 4)
    if gltf is None:
        fail(f"{path}: no JSON chunk")
    for i, buffer in enumerate(gltf.get("buffers", [])):
        if i > 0 or "uri" in buffer:
            fail(f"{path}: buffer {i} is not the GLB's binary chunk (only self-contained .glb files are wrapped)")
    return gltf, binary


class Accessors:
    def __init__(self, gltf, binary):
        self.gltf, self.binary = gltf, binary

    def read(self, index):
        """The accessor's elements as tuples of floats (normalized integers mapped to [0, 1] / [-1, 1])."""
        a = self.gltf["accessors"][index]
        if "sparse" in a:
            fail(f"accessors[{index}]: sparse accessors are not read by this helper")
        n, ctype = COUNT[a["type"]], a["componentType"]
        if "bufferView" not in a:
            return [tuple([0.0] * n)] * a["count"]
        view = self.gltf["bufferViews"][a["bufferView"]]
        if view.get("buffer", 0) != 0:
            fail(f"accessors[{index}]: not in the binary chunk")
        fmt = "<" + COMPONENT[ctype] * n
        size = struct.calcsize(fmt)
        stride = view.get("byteStride") or size
        base = view.get("byteOffset", 0) + a.get("byteOffset", 0)
        scale = NORMALIZE.get(ctype) if a.get("normalized") else None
        out = []
        for k in range(a["count"]):
            v = struct.unpack_from(fmt, self.binary, base + k * stride)
            out.append(tuple(max(x / scale, -1.0) for x in v) if scale else tuple(float(x) for x in v))
        return out

    def box(self, index):
        a = self.gltf["accessors"][index]
        if "min" in a and "max" in a:
            return a["min"][:3], a["max"][:3]
        points = self.read(index)  # min/max are required for POSITION; be lenient
        return [min(p[i] for p in points) for i in range(3)], [max(p[i] for p in points) for i in range(3)]


# --- matrices (column-major 4x4 as lists of 16, as glTF stores them) ---------------------------
IDENTITY = [1.0, 0, 0, 0, 0, 1.0, 0, 0, 0, 0, 1.0, 0, 0, 0, 0, 1.0]


def mat_mul(a, b):
    return [sum(a[k * 4 + r] * b[c * 4 + k] for k in range(4)) for c in range(4) for r in range(4)]


def transform_point(m, p):
    return [m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r] for r in range(3)]


def trs_matrix(t, q, s):
    x, y, z, w = q
    n = math.sqrt(x * x + y * y + z * z + w * w) or 1.0
    x, y, z, w = x / n, y / n, z / n, w / n
    r = [1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w),
         2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w),
         2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y)]
    return [r[0] * s[0], r[1] * s[0], r[2] * s[0], 0.0,
            r[3] * s[1], r[4] * s[1], r[5] * s[1], 0.0,
            r[6] * s[2], r[7] * s[2], r[8] * s[2], 0.0,
            t[0], t[1], t[2], 1.0]


def quat_from_axes(x, y, z):
    """The unit quaternion (x, y, z, w) of the rotation whose columns are the axes x, y, z."""
    m00, m11, m22 = x[0], y[1], z[2]
    trace = m00 + m11 + m22
    if trace > 0:
        s = math.sqrt(trace + 1.0) * 2
        q = [(y[2] - z[1]) / s, (z[0] - x[2]) / s, (x[1] - y[0]) / s, 0.25 * s]
    elif m00 > m11 and m00 > m22:
        s = math.sqrt(1.0 + m00 - m11 - m22) * 2
        q = [0.25 * s, (y[0] + x[1]) / s, (z[0] + x[2]) / s, (y[2] - z[1]) / s]
    elif m11 > m22:
        s = math.sqrt(1.0 + m11 - m00 - m22) * 2
        q = [(y[0] + x[1]) / s, 0.25 * s, (z[1] + y[2]) / s, (z[0] - x[2]) / s]
    else:
        s = math.sqrt(1.0 + m22 - m00 - m11) * 2
        q = [(z[0] + x[2]) / s, (z[1] + y[2]) / s, 0.25 * s, (x[1] - y[0]) / s]
    n = math.sqrt(sum(c * c for c in q))
    return [c / n for c in q]


def normalize(v):
    n = math.sqrt(sum(c * c for c in v))
    return [c / n for c in v]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def look_along(direction, up=(0.0, 1.0, 0.0)):
    """Rotation turning the node's -Z to `direction`, its +Y towards `up`."""
    z = normalize([-c for c in direction])
    x = normalize(cross(up, z))
    return quat_from_axes(x, cross(z, x), z)


# --- animation ---------------------------------------------------------------------------------
def clip_duration(gltf, animation):
    return max(gltf["accessors"][s["input"]].get("max", [0.0])[0] for s in animation["samplers"])


def choose_clip(gltf, wanted):
    animations = gltf.get("animations", [])
    if not animations:
        return None
    names = [a.get("name", f"animation{i}") for i, a in enumerate(animations)]
    if wanted:
        if wanted not in names:
            fail(f"--clip {wanted}: the asset's clips are {', '.join(names)}")
        return names.index(wanted)
    for i, name in enumerate(names):
        if any(word in name.lower() for word in ("walk", "move", "run")):
            return i
    return max(range(len(animations)), key=lambda i: clip_duration(gltf, animations[i]))


def sample_channel(acc, sampler, t):
    times = [k[0] for k in acc.read(sampler["input"])]
    values = acc.read(sampler["output"])
    mode = sampler.get("interpolation", "LINEAR")
    if mode == "CUBICSPLINE":
        values = values[1::3]  # the value of each (in-tangent, value, out-tangent) triple
    if t <= times[0]:
        return list(values[0])
    if t >= times[-1]:
        return list(values[-1])
    k = max(i for i in range(len(times)) if times[i] <= t)
    if mode == "STEP":
        return list(values[k])
    u = (t - times[k]) / (times[k + 1] - times[k])
    a, b = values[k], values[k + 1]
    if len(a) == 4 and sum(x * y for x, y in zip(a, b)) < 0:
        b = [-x for x in b]  # the short way round (a normalised lerp is enough for bounds)
    return [x + (y - x) * u for x, y in zip(a, b)]


def posed_locals(gltf, acc, clip, t):
    locals_ = []
    for node in gltf.get("nodes", []):
        locals_.append({"t": list(node.get("translation", [0, 0, 0])),
                        "r": list(node.get("rotation", [0, 0, 0, 1])),
                        "s": list(node.get("scale", [1, 1, 1])), "matrix": node.get("matrix")})
    if clip is not None:
        animation = gltf["animations"][clip]
        for channel in animation["channels"]:
            path, node = channel["target"].get("path"), channel["target"].get("node")
            if node is None or path not in ("translation", "rotation", "scale"):
                continue
            value = sample_channel(acc, animation["samplers"][channel["sampler"]], t)
            locals_[node][{"translation": "t", "rotation": "r", "scale": "s"}[path]] = value
            locals_[node]["matrix"] = None  # animated nodes have TRS
    return [l["matrix"] if l["matrix"] else trs_matrix(l["t"], l["r"], l["s"]) for l in locals_]


# --- the asset's scene: world transforms, bounds, triangles ------------------------------------
def scene_roots(gltf):
    scenes = gltf.get("scenes", [])
    if scenes:
        return scenes[gltf.get("scene", 0)].get("nodes", [])
    children = {c for n in gltf.get("nodes", []) for c in n.get("children", [])}
    return [i for i in range(len(gltf.get("nodes", []))) if i not in children]


def world_matrices(gltf, locals_):
    world = {}

    def visit(i, parent):
        world[i] = mat_mul(parent, locals_[i])
        for c in gltf["nodes"][i].get("children", []):
            visit(c, world[i])

    for root in scene_roots(gltf):
        visit(root, IDENTITY)
    return world


def primitive_triangles(gltf, primitive):
    mode = primitive.get("mode", 4)
    if "indices" in primitive:
        n = gltf["accessors"][primitive["indices"]]["count"]
    else:
        n = gltf["accessors"][primitive["attributes"]["POSITION"]]["count"]
    return n // 3 if mode == 4 else max(n - 2, 0) if mode in (5, 6) else 0


def bounds_and_triangles(gltf, acc, world):
    lo, hi, triangles = [math.inf] * 3, [-math.inf] * 3, 0

    def add(p):
        for i in range(3):
            lo[i], hi[i] = min(lo[i], p[i]), max(hi[i], p[i])

    for i, m in world.items():
        node = gltf["nodes"][i]
        if "mesh" not in node:
            continue
        skin = gltf["skins"][node["skin"]] if "skin" in node else None
        joints = []
        if skin:
            ibms = acc.read(skin["inverseBindMatrices"]) if "inverseBindMatrices" in skin else None
            for k, j in enumerate(skin["joints"]):
                joints.append(mat_mul(world.get(j, IDENTITY), list(ibms[k]) if ibms else IDENTITY))
        for primitive in gltf["meshes"][node["mesh"]]["primitives"]:
            triangles += primitive_triangles(gltf, primitive)
            attributes = primitive["attributes"]
            if skin and "JOINTS_0" in attributes and "WEIGHTS_0" in attributes:
                # A skinned mesh: the node's own transform is not used (glTF), its joints pose it.
                positions = acc.read(attributes["POSITION"])
                weights = acc.read(attributes["WEIGHTS_0"])
                for p, js, ws in zip(positions, acc.read(attributes["JOINTS_0"]), weights):
                    q = [0.0, 0.0, 0.0]
                    for j, w in zip(js, ws):
                        if w > 0:
                            r = transform_point(joints[int(j)], p)
                            q = [a + w * b for a, b in zip(q, r)]
                    total = sum(ws)
                    add([c / total for c in q] if total > 0 else transform_point(m, p))
            else:
                bmin, bmax = acc.box(attributes["POSITION"])
                for c in range(8):
                    add(transform_point(m, [bmax[k] if c >> k & 1 else bmin[k] for k in range(3)]))
    if lo[0] == math.inf:
        fail("the asset's scene holds no mesh")
    return lo, hi, triangles


# --- the wrapper -------------------------------------------------------------------------------
def append_view(gltf, blob, data, target):
    blob.extend(b"\0" * (-len(blob) % 4))
    gltf.setdefault("bufferViews", []).append(
        {"buffer": 0, "byteOffset": len(blob), "byteLength": len(data), "target": target})
    blob.extend(data)
    return len(gltf["bufferViews"]) - 1


def append_accessor(gltf, view, component, count, type_, lo=None, hi=None):
    a = {"bufferView": view, "componentType": component, "count": count, "type": type_}
    if lo is not None:
        a["min"], a["max"] = lo, hi
    gltf.setdefault("accessors", []).append(a)
    return len(gltf["accessors"]) - 1


def wrap(src, dst, clip_name, ground_casts=False):
    gltf, binary = read_glb(src)
    acc = Accessors(gltf, binary)
    clip = choose_clip(gltf, clip_name)
    clip_names = [a.get("name", f"animation{i}") for i, a in enumerate(gltf.get("animations", []))]
    time = 0.0
    if clip is not None:
        time = 0.5 * clip_duration(gltf, gltf["animations"][clip])
        gltf["animations"] = [gltf["animations"][clip]]
    world = world_matrices(gltf, posed_locals(gltf, acc, 0 if clip is not None else None, time))
    lo, hi, triangles = bounds_and_triangles(gltf, acc, world)
    extent = [b - a for a, b in zip(lo, hi)]
    size = max(extent)
    if not size > 0:
        fail("the model's bounds are a point")
    if extent[1] < FLAT * size:
        print(f"flat: {extent[1]:.3g} high for {size:.3g} across, nothing to cast a shadow on a ground below it",
              file=sys.stderr)
        sys.exit(3)
    centre = [(a + b) / 2 for a, b in zip(lo, hi)]
    ground_y = lo[1] - GROUND_GAP * size

    blob = bytearray(binary)
    # Ground: a 4 S square under the bounds' centre, facing +Y.
    half = GROUND_HALF * size
    x0, x1, z0, z1 = centre[0] - half, centre[0] + half, centre[2] - half, centre[2] + half
    corners = [(x0, ground_y, z0), (x0, ground_y, z1), (x1, ground_y, z1), (x1, ground_y, z0)]
    pos = append_view(gltf, blob, b"".join(struct.pack("<3f", *c) for c in corners), 34962)
    nrm = append_view(gltf, blob, struct.pack("<3f", 0, 1, 0) * 4, 34962)
    idx = append_view(gltf, blob, struct.pack("<6H", 0, 1, 2, 0, 2, 3), 34963)
    ground_mesh = {"name": "real_assets_ground", "primitives": [{
        "attributes": {"POSITION": append_accessor(gltf, pos, 5126, 4, "VEC3", [x0, ground_y, z0], [x1, ground_y, z1]),
                       "NORMAL": append_accessor(gltf, nrm, 5126, 4, "VEC3")},
        "indices": append_accessor(gltf, idx, 5123, 6, "SCALAR"),
        "material": len(gltf.setdefault("materials", []))}]}
    gltf["materials"].append({"name": "real_assets_ground", "pbrMetallicRoughness": {
        "baseColorFactor": [0.55, 0.55, 0.55, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0}})
    gltf.setdefault("meshes", []).append(ground_mesh)
    gltf["buffers"] = [{"byteLength": len(blob), "uri": os.path.basename(dst)[:-len(".gltf")] + ".bin"}]

    # Sun: shines along d (45 degrees from vertical); its shadow falls along d's horizontal part.
    d = [math.sin(SUN_TILT) * math.cos(SUN_AZIMUTH), -math.cos(SUN_TILT), math.sin(SUN_TILT) * math.sin(SUN_AZIMUTH)]
    shadow = {"technique": "pcss", "mapSize": 2048, "angularRadius": SUN_ANGULAR_RADIUS}
    extensions = gltf.setdefault("extensions", {})
    lights = extensions.setdefault("KHR_lights_punctual", {}).setdefault("lights", [])
    lights.append({"name": "real_assets_sun", "type": "directional", "color": [1.0, 0.95, 0.88],
                   "intensity": 3.0, "extras": {"shadow": shadow}})
    used = gltf.setdefault("extensionsUsed", [])
    if "KHR_lights_punctual" not in used:
        used.append("KHR_lights_punctual")

    # Camera: frames the bounding sphere of the model's box and that box projected along d onto
    # the ground (its shadow), from the front, above.
    points = [[hi[k] if c >> k & 1 else lo[k] for k in range(3)] for c in range(8)]
    points += [[p[0] + d[0] * (p[1] - ground_y) / -d[1], ground_y, p[2] + d[2] * (p[1] - ground_y) / -d[1]]
               for p in points]
    target = [(min(p[k] for p in points) + max(p[k] for p in points)) / 2 for k in range(3)]
    view = [-math.cos(CAMERA_ELEVATION) * math.sin(CAMERA_AZIMUTH), -math.sin(CAMERA_ELEVATION),
            -math.cos(CAMERA_ELEVATION) * math.cos(CAMERA_AZIMUTH)]
    right = normalize(cross(view, [0.0, 1.0, 0.0]))
    up = cross(right, view)
    tan_v = math.tan(CAMERA_YFOV / 2)
    tan_h = tan_v * ASPECT
    # The nearest eye on the line through the target along -view that sees every point, 5 % margin.
    distance = 0.0
    for p in points:
        q = [a - b for a, b in zip(p, target)]
        depth = sum(a * b for a, b in zip(q, view))
        distance = max(distance, abs(sum(a * b for a, b in zip(q, right))) / tan_h - depth,
                       abs(sum(a * b for a, b in zip(q, up))) / tan_v - depth)
    distance *= 1.05
    eye = [t - distance * v for t, v in zip(target, view)]
    gltf.setdefault("cameras", []).append({"name": "real_assets_camera", "type": "perspective", "perspective": {
        "yfov": CAMERA_YFOV, "znear": 0.02 * distance, "zfar": distance + 4 * GROUND_HALF * size}})

    nodes = gltf.setdefault("nodes", [])
    first = len(nodes)
    nodes.append({"name": "real_assets_camera", "camera": len(gltf["cameras"]) - 1,
                  "translation": eye, "rotation": look_along(view)})
    nodes.append({"name": "real_assets_sun", "rotation": look_along(d, (0.0, 0.0, -1.0)),
                  "translation": [centre[0], hi[1] + size, centre[2]],
                  "extensions": {"KHR_lights_punctual": {"light": len(lights) - 1}}})
    nodes.append({"name": "real_assets_ground", "mesh": len(gltf["meshes"]) - 1,
                  "extras": {"shadow": {"cast": ground_casts, "receive": True}}})
    roots = [first, first + 1, first + 2] + list(scene_roots(gltf))
    if gltf.get("scenes"):
        gltf["scenes"][gltf.get("scene", 0)]["nodes"] = roots
    else:
        gltf["scenes"], gltf["scene"] = [{"nodes": roots}], 0

    with open(dst[:-len(".gltf")] + ".bin", "wb") as f:
        f.write(blob)
    with open(dst, "w") as f:
        json.dump(gltf, f)
    return {"source": os.path.basename(src), "triangles": triangles,
            "boundsMin": lo, "boundsMax": hi, "extent": extent, "size": size,
            "clips": clip_names, "clip": clip_names[clip] if clip is not None else None, "time": time,
            "light": 0, "shadow": shadow, "sunDirection": d, "cameraDistance": distance}


# --- checks of the results ---------------------------------------------------------------------
def png_mean(path):
    """Mean of an 8-bit RGB/RGBA/grey PNG's samples in [0, 1] (non-interlaced, as the engine writes)."""
    data = open(path, "rb").read()
    offset, idat, width = 8, b"", 0
    while offset < len(data):
        length, kind = struct.unpack_from(">I4s", data, offset)
        body = data[offset + 8:offset + 8 + length]
        if kind == b"IHDR":
            width, _, depth, colour = struct.unpack_from(">IIBB", body)
            if depth != 8:
                return None
            channels = {0: 1, 2: 3, 4: 2, 6: 4}[colour]
        elif kind == b"IDAT":
            idat += body
        offset += 12 + length
    raw, row_bytes = zlib.decompress(idat), width * channels
    previous, total, count = bytearray(row_bytes), 0, 0
    for y in range(len(raw) // (row_bytes + 1)):
        kind, row = raw[y * (row_bytes + 1)], bytearray(raw[y * (row_bytes + 1) + 1:(y + 1) * (row_bytes + 1)])
        for i in range(row_bytes):
            a = row[i - channels] if i >= channels else 0
            b, c = previous[i], previous[i - channels] if i >= channels else 0
            if kind == 1:
                row[i] = (row[i] + a) & 255
            elif kind == 2:
                row[i] = (row[i] + b) & 255
            elif kind == 3:
                row[i] = (row[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                row[i] = (row[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        total += sum(row)
        count += row_bytes
        previous = row
    return total / count / 255.0 if count else None


def table(work, assets):
    rows, notes = [], []
    for asset in assets:
        base = os.path.join(work, asset)
        status = open(os.path.join(base, "status")).read().strip()
        if status != "ok":
            notes.append(f"{asset}: {status}")
            continue
        info = json.load(open(os.path.join(base, "info.json")))
        techniques = [t for t in open(os.path.join(base, "techniques")).read().split()]
        extent = "x".join(f"{e:.3g}" for e in info["extent"])
        light = info["light"]
        truth_counts = None
        for technique in techniques:
            result_path = os.path.join(base, f"{technique}.json")
            stats_path = os.path.join(base, technique, "stats.json")
            if not (os.path.exists(result_path) and os.path.exists(stats_path)):
                rows.append(f"| {asset} | {info['triangles']} | {extent} | {technique} | failed | | | | | |")
                notes.append(f"{asset} / {technique}: no result (see {base}/{technique}.log)")
                continue
            result = next(l for l in json.load(open(result_path))["lights"] if l["index"] == light)
            stats = json.load(open(stats_path))
            timings = stats["timingsMs"]
            shadow_ms = timings["shadowPassesTotal"]["median"]
            main_ms = timings["mainPassesTotal"]["median"]
            c = result["counts"]
            truth_counts = c
            rows.append(f"| {asset} | {info['triangles']} | {extent} | {technique} | {result['rmse']:.4f} | "
                        f"{result['penumbraRmse']:.4f} | {100 * result['leakFraction']:.2f} % | "
                        f"{100 * result['acneFraction']:.2f} % | {shadow_ms:.1f} | {main_ms:.1f} |")
            colour = png_mean(os.path.join(base, technique, "color.png"))
            if colour is not None and colour < 0.01:
                notes.append(f"{asset} / {technique}: color.png is black (mean {colour:.4f})")
            if result["leakFraction"] > 0.05 or result["interiorLeakFraction"] > 0.05:
                notes.append(f"{asset} / {technique}: light in the true umbra, {100 * result['leakFraction']:.1f} % "
                             f"of {c['umbra']} umbra pixels above 0.5 (interior umbra: "
                             f"{100 * result['interiorLeakFraction']:.1f} % of {c['interiorUmbra']} above 0.1)")
            if result["acneFraction"] > 0.01:
                notes.append(f"{asset} / {technique}: false shadow in {100 * result['acneFraction']:.1f} % of "
                             f"{c['lit']} lit pixels (mean darkening {result['acneMeanDarkening']:.3f})")
            if c["nonFinite"]:
                notes.append(f"{asset} / {technique}: {c['nonFinite']} NaN/Inf pixels")
            codes = sorted({w["code"] for w in stats.get("warnings", [])})
            if codes:
                notes.append(f"{asset} / {technique}: warnings {', '.join(codes)}")
        if truth_counts is not None:
            shadowed = truth_counts["umbra"] + truth_counts["penumbra"]
            if shadowed < 0.01 * max(truth_counts["receivers"], 1):
                notes.append(f"{asset}: almost no shadow in view ({shadowed} of {truth_counts['receivers']} "
                             "receiver pixels in umbra or penumbra)")
    print("| asset | triangles | bounds (units) | technique | RMSE | penumbra RMSE | umbra leak | false shadow | shadow ms | main ms |")
    print("|---|---:|---|---|---:|---:|---:|---:|---:|---:|")
    for row in rows:
        print(row)
    return notes


def main():
    args = sys.argv[1:]
    if len(args) >= 3 and args[0] == "wrap":
        clip, ground_casts, rest = None, False, args[3:]
        while rest:
            if rest[0] == "--clip" and len(rest) > 1:
                clip, rest = rest[1], rest[2:]
            elif rest[0] == "--ground-casts":
                ground_casts, rest = True, rest[1:]
            else:
                fail(f"wrap: unknown argument {rest[0]}")
        if not args[2].endswith(".gltf"):
            fail("wrap: the output must be a .gltf path")
        print(json.dumps(wrap(args[1], args[2], clip, ground_casts), indent=1))
        return 0
    if len(args) >= 3 and args[0] == "table":
        notes = table(args[1], args[2:])
        print()
        print("\n".join(f"- {n}" for n in notes) if notes else "No result looks wrong by the checks below.")
        return 0
    print(__doc__, file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main())
