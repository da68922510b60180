#!/usr/bin/env python3
"""Helper of samples/asset_gallery.sh: renders the README's gallery of third-party glTF assets.

    python3 samples/asset_gallery.py RENDER RAYLIB_GIT BEVY_GIT IMAGES SIZE APNG_SIZE > SECTION.md

Reads each asset of ASSETS out of its repository's git snapshot (HEAD) into a temporary folder,
with every buffer and image file a .gltf names, and renders it as it is with RENDER (the
shadow_render program): one still at SIZE (WxH) in the middle of the clip named, written to
IMAGES/<name>.png, and for the assets marked so one period of that clip at APNG_SIZE, joined by
samples/scenes/make_apng.py into IMAGES/<name>.apng.png. Prints the gallery's Markdown (a row
per asset: image, source, triangles, what the file exercises, the shadow technique, the
warnings stats.json lists) on stdout and its progress on stderr. An asset that does not load is
a row with the error instead of an image. Exit code 2, before anything is written, when a
snapshot holds none of its repository's assets (the wrong repository).
"""
import json
import os
import struct
import subprocess
import sys
import tempfile
import urllib.parse
from collections import namedtuple

HERE = os.path.dirname(os.path.abspath(__file__))
APNG_FPS = 10  # frames per second of an animated loop, within APNG_FRAMES frames
APNG_FRAMES = (8, 24)

# repo: "raylib" or "bevy"; clip: the animation shadow_render plays (None: the file's first, or
# none); apng: also one loop of it as an animated PNG.
Asset = namedtuple("Asset", "repo path clip apng")
ASSETS = [
    Asset("raylib", "examples/models/resources/models/gltf/robot.glb", "Robot_Dance", True),
    Asset("raylib", "examples/models/resources/models/gltf/greenman.glb", "2_move", False),
    Asset("raylib", "examples/shaders/resources/models/old_car_new.glb", None, False),
    Asset("raylib", "examples/models/resources/models/gltf/raylib_logo_3d.glb", None, False),
    Asset("bevy", "assets/models/animated/Fox.glb", "Run", True),
    Asset("bevy", "assets/models/animated/MorphStressTest.gltf", "TheWave", False),
    Asset("bevy", "assets/models/FlightHelmet/FlightHelmet.gltf", None, False),
    Asset("bevy", "assets/models/GolfBall/GolfBall.glb", None, False),
    Asset("bevy", "assets/models/CornellBox/CornellBox.glb", None, False),
    Asset("bevy", "assets/models/AlienCake/cakeBirthday.glb", None, False),
    Asset("bevy", "assets/models/ship/craft_speederD.gltf", None, False),
    Asset("bevy", "assets/models/DepthOfFieldExample/DepthOfFieldExample.glb", None, False),
    Asset("bevy", "assets/models/MixedLightingExample/MixedLightingExample.gltf", None, False),
    # Does not load (its images are KTX2 files, not PNG or JPEG): its row shows the error.
    Asset("bevy", "assets/models/AnisotropyBarnLamp/AnisotropyBarnLamp.gltf", None, False),
]
# The rest of the two repositories' models, and why they are not in the gallery.
SKIPPED = [
    ("raylib", "examples/shaders/resources/models/robot.glb", "the same file as the robot above"),
    ("raylib", "examples/shaders/resources/models/plane.glb", "a flat quad: it lies on the ground, no shadow to show"),
    ("raylib", "examples/models/resources/models/gltf/greenman_{hat,shield,sword}.glb",
     "the greenman's props, static pieces of 44-80 triangles"),
    ("bevy", "assets/models/PalmTree/PalmTree.gltf",
     "a water plane 390 units wide around a palm tree 4 high: framed whole, the tree is a few pixels"),
    ("bevy", "assets/models/terrain/", "height fields (one 2.9 MB), nothing standing on them"),
    ("bevy", "assets/models/VolumetricFogExample/VolumetricFogExample.glb",
     "a closed room made to be seen from inside through volumetric fog"),
    ("bevy", "assets/models/FlightHelmetLowPoly/", "its .bin is not in the snapshot"),
    ("bevy", "assets/models/SimpleSkin/SimpleSkin.gltf", "8 triangles; the robot and the fox show skins"),
    ("bevy", "assets/models/{AlienCake/alien,AlienCake/tile,cubes/Cubes,Faces/faces}.glb",
     "a few boxes, tiles or text cards each"),
    ("bevy", "assets/models/IrradianceVolumeExample/IrradianceVolumeExample.glb", "a room of 32 triangles"),
    ("bevy", "assets/models/{cube,sphere,torus,barycentric,GltfPrimitives,extras,TonemappingTest}/",
     "test shapes and tone-map patterns of bevy's own examples"),
]


def name_of(asset):
    """The asset's image name: its file name without the extension."""
    return os.path.splitext(os.path.basename(asset.path))[0]


def log(message):
    print(f"asset_gallery: {message}", file=sys.stderr)


def git(git_dir, *args):
    """git run on the snapshot, its output captured (bytes)."""
    return subprocess.run(["git", f"--git-dir={git_dir}", *args], capture_output=True)


def git_blob(git_dir, path):
    """The bytes of HEAD:path in the snapshot, or None when it holds no such file."""
    run = git(git_dir, "cat-file", "blob", f"HEAD:{path}")
    return run.stdout if run.returncode == 0 else None


def gltf_json(data):
    """The JSON of a .glb (its first chunk) or a .gltf."""
    if data[:4] == b"glTF":
        (length,) = struct.unpack_from("<I", data, 12)
        data = data[20:20 + length]
    return json.loads(data)


def extract(git_dir, path, folder):
    """Writes `path` and the files its buffers and images name under `folder`, at their paths in
    the repository; returns the local path and the glTF JSON, or raises LookupError."""
    files = [path]
    data = git_blob(git_dir, path)
    if data is None:
        raise LookupError(f"{path}: not in the snapshot")
    gltf = gltf_json(data)
    for item in gltf.get("buffers", []) + gltf.get("images", []):
        uri = item.get("uri", "")
        if uri and not uri.startswith("data:"):
            files.append(os.path.normpath(os.path.join(os.path.dirname(path), urllib.parse.unquote(uri))))
    for name in files:
        data = git_blob(git_dir, name)
        if data is None:
            raise LookupError(f"{path}: {name}, which it names, is not in the snapshot")
        local = os.path.join(folder, name)
        os.makedirs(os.path.dirname(local), exist_ok=True)
        with open(local, "wb") as f:
            f.write(data)
    return os.path.join(folder, path), gltf, len(files) - 1


def triangles(gltf):
    """Triangles drawn: TRIANGLES primitives of every mesh node instance of the default scene."""
    scenes = gltf.get("scenes", [])
    stack = list(scenes[gltf.get("scene", 0)]["nodes"]) if scenes else list(range(len(gltf.get("nodes", []))))
    seen, total = set(), 0
    while stack:
        index = stack.pop()
        if index in seen:
            continue
        seen.add(index)
        node = gltf["nodes"][index]
        stack.extend(node.get("children", []))
        for primitive in gltf["meshes"][node["mesh"]]["primitives"] if "mesh" in node else []:
            if primitive.get("mode", 4) == 4:
                accessor = primitive.get("indices", primitive["attributes"]["POSITION"])
                total += gltf["accessors"][accessor]["count"] // 3
    return total


def clip_index(gltf, clip):
    names = [a.get("name", "") for a in gltf.get("animations", [])]
    return names.index(clip) if clip in names else 0


def clip_duration(gltf, clip):
    animations = gltf.get("animations", [])
    if not animations:
        return 0.0
    samplers = animations[clip_index(gltf, clip)]["samplers"]
    return max(gltf["accessors"][s["input"]].get("max", [0.0])[0] for s in samplers)


def count(n, noun):
    return f"{n} {noun}" + ("" if n == 1 else "s")


def material_features(materials):
    """Material features beyond base colour and metallic-roughness factors."""
    out = []
    if any("normalTexture" in m for m in materials):
        out.append("normal maps")
    if any("emissiveTexture" in m or any(m.get("emissiveFactor", [])) for m in materials):
        out.append("emission")
    if any("KHR_texture_transform" in json.dumps(m) for m in materials):
        out.append("texture transforms")
    for mode in sorted({m.get("alphaMode", "OPAQUE") for m in materials} - {"OPAQUE"}):
        out.append(f"alpha `{mode}`" + (" (drawn as a cut-out)" if mode == "BLEND" else ""))
    return out


def exercises(gltf, external, clip, time):
    """What the file asks of the loader and renderer, in a few words."""
    out = []
    if gltf.get("images"):
        out.append(count(len(gltf["images"]), "texture image"))
    out += material_features(gltf.get("materials", []))
    joints = max((len(s["joints"]) for s in gltf.get("skins", [])), default=0)
    if joints:
        out.append(f"skin ({joints} joints)")
    targets = max((len(p.get("targets", [])) for m in gltf.get("meshes", []) for p in m["primitives"]), default=0)
    if targets:
        out.append(f"morph targets ({targets})")
    animations = gltf.get("animations", [])
    if animations:
        name = animations[clip_index(gltf, clip)].get("name", "0")
        out.append(f"{len(animations)} clips, `{name}` at {time:.2f} s")
    lights = len(gltf.get("extensions", {}).get("KHR_lights_punctual", {}).get("lights", []))
    if lights:
        out.append("its own light" if lights == 1 else f"its own {lights} lights")
    if external:
        out.append(count(external, "external file"))
    return ", ".join(out) or "geometry and material factors only"


def render(program, scene, out, size, clip, time, frames=1, dt=0.0):
    """Runs shadow_render; returns its stats.json, or raises RuntimeError with its last message."""
    command = [program, scene, "--out", out, "--size", size, "--aov", "color", "--time", f"{time:.6g}"]
    if clip:
        command += ["--animation", clip]
    if frames > 1:
        command += ["--frames", str(frames), "--dt", f"{dt:.6g}", "--frame-images"]
    run = subprocess.run(command, capture_output=True, text=True)
    if run.returncode != 0:
        lines = [line for line in run.stderr.splitlines() if line.strip()] or [f"exit code {run.returncode}"]
        raise RuntimeError(lines[-1].replace("shadow_render: ", "", 1))
    with open(os.path.join(out, "stats.json")) as f:
        return json.load(f)


def technique(stats):
    rig = any(w["code"] == "DefaultRigAdded" for w in stats["warnings"])
    if rig:
        return f"`{stats['lights'][0]['technique']}` sun of the default rig"
    lights = stats["lights"]
    return ", ".join(f"`{light['technique']}` {light['type']} `{light['node']}` (the file's)" for light in lights)


def warnings(stats, scene):
    """stats.json's warnings but the default rig's, without the temporary folder's path."""
    shown = [f"`{w['code']}`: {w['message'].removeprefix(scene + ': ')}" for w in stats["warnings"]
             if w["code"] != "DefaultRigAdded"]
    return "<br>".join(shown) or "none"


def render_loop(program, scene, work, size, clip, duration, out):
    """One period of the clip as an animated PNG at about APNG_FPS frames a second."""
    n = min(APNG_FRAMES[1], max(APNG_FRAMES[0], round(duration * APNG_FPS)))
    render(program, scene, work, size, clip, 0.0, n, duration / n)
    frames = sorted(os.path.join(work, "frames", f) for f in os.listdir(os.path.join(work, "frames")))
    fps = max(1, round(n / duration))
    subprocess.run([sys.executable, os.path.join(HERE, "scenes", "make_apng.py"), out, str(fps)] + frames, check=True)


def gallery_row(asset, git_dir, program, work, images, sizes):
    name = name_of(asset)
    source = f"**{name}**<br>{asset.repo} `{asset.path}`"
    try:
        scene, gltf, external = extract(git_dir, asset.path, os.path.join(work, name))
        duration = clip_duration(gltf, asset.clip)
        stats = render(program, scene, os.path.join(work, name, "still"), sizes[0], asset.clip, duration / 2)
        if asset.apng:
            render_loop(program, scene, os.path.join(work, name, "loop"), sizes[1], asset.clip, duration,
                        os.path.join(images, f"{name}.apng.png"))
    except (LookupError, RuntimeError, ValueError) as error:  # ValueError: JSON the parser refused
        message = str(error).replace(os.path.join(work, name) + os.sep, "")
        log(f"{name}: {message}")
        return f"| (not drawn) | {source} | | | | failed: {message} |"
    os.replace(os.path.join(work, name, "still", "color.png"), os.path.join(images, f"{name}.png"))
    log(f"{name}: rendered")
    return (f"| ![{name}](samples/images/assets/{name}.png) | {source} | {triangles(gltf)} | "
            f"{exercises(gltf, external, asset.clip, duration / 2)} | {technique(stats)} | {warnings(stats, scene)} |")


def print_section(rows, snapshots, sizes, images):
    commits = {repo: git(d, "rev-parse", "HEAD").stdout.decode().strip()[:12] for repo, d in snapshots.items()}
    print(f"""Read at raylib `{commits['raylib']}` and bevy `{commits['bevy']}`. Stills
`--size {sizes[0]}` at the middle of the clip named (`--animation CLIP --time T`); loops `--size {sizes[1]}`,
one period of the clip at about {APNG_FPS} frames a second; every other setting `shadow_render`'s default.
Triangles: those of the default scene's mesh nodes.
""")
    print("| image | asset | triangles | exercises | technique | warnings (`stats.json`) |")
    print("|---|---|---:|---|---|---|")
    print("\n".join(rows))
    loops = [a for a in ASSETS if a.apng and os.path.exists(os.path.join(images, f"{name_of(a)}.apng.png"))]
    if loops:
        print()
        print("| " + " | ".join(f"{name_of(a)}, `{a.clip}`, one loop (APNG)" for a in loops) + " |")
        print("|" + "---|" * len(loops))
        print("| " + " | ".join(f"![{name_of(a)}](samples/images/assets/{name_of(a)}.apng.png)" for a in loops) + " |")
    print()
    print("Not in the gallery:")
    print()
    for repo, path, why in SKIPPED:
        print(f"- {repo} `{path}`: {why}")


def main(argv):
    if len(argv) != 7:
        print(__doc__, file=sys.stderr)
        return 2
    program, raylib_git, bevy_git, images, size, apng_size = argv[1:]
    snapshots = {"raylib": raylib_git, "bevy": bevy_git}
    for repo, git_dir in snapshots.items():
        if all(git(git_dir, "cat-file", "-e", f"HEAD:{a.path}").returncode for a in ASSETS if a.repo == repo):
            log(f"{git_dir}: holds none of the gallery's {repo} assets; is it the {repo} repository?")
            return 2
    os.makedirs(images, exist_ok=True)
    with tempfile.TemporaryDirectory() as work:
        rows = [gallery_row(a, snapshots[a.repo], program, work, images, (size, apng_size)) for a in ASSETS]
    print_section(rows, snapshots, (size, apng_size), images)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
