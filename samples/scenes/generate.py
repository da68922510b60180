#!/usr/bin/env python3
"""Writes the animated sample scenes of samples/scenes/ as self-contained glTF 2.0 files.

Every asset is made here (from the parts in scene_kit.py beside it), with nothing but the Python 3
standard library: meshes, skins, the PNG textures and the animations. Each scene is one `.gltf`
with its buffer and images embedded as base64 data URIs, and each shows something a shadow
module must get right (README.md in this folder says what). Lights use KHR_lights_punctual; their shadow settings are the engine's
`extras.shadow` (the project README's "glTF scenes" section).

Conventions are glTF's: metres, +Y up, right-handed; lights and cameras look down their node's
-Z. Every animation is one clip whose channels start and end on the same value, so the engine's
looping (clip time = t mod duration) has no seam.

The output is deterministic: no clocks, no `random` (a fixed linear congruential generator),
floats rounded before they reach the JSON. Run `python3 samples/scenes/generate.py` and commit
what changed.
"""

import math
import os
import sys

sys.dont_write_bytecode = True  # no __pycache__ left in the source tree
from scene_kit import (  # noqa: E402
    CLAMP_TO_EDGE, Gltf, Lcg, add, arch, box, card, checker_png, cylinder, lathe, lattice_png,
    leaf_png, merge, normalize, plane, quat_axis_angle, quat_mul, r6, roll_keys, scale,
    shuttle_keys, sphere, spin_keys, swing_keys, torus, transformed)

HERE = os.path.dirname(os.path.abspath(__file__))


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
