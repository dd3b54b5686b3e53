#!/usr/bin/env python3
"""Regenerates faucet_spout.obj and faucet_handle.obj (closed, outward-wound).

Object frame, metres, z up. Run from anywhere: python3 make_faucet_meshes.py
"""
import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))


def signed_volume(verts, tris):
    v = 0.0
    for a, b, c in tris:
        (ax, ay, az), (bx, by, bz), (cx, cy, cz) = verts[a], verts[b], verts[c]
        v += (ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx)) / 6
    return v


def write_obj(name, header, verts, tris):
    if signed_volume(verts, tris) < 0:  # make the winding outward
        tris = [(a, c, b) for a, b, c in tris]
    lo = [min(v[k] for v in verts) for k in range(3)]
    hi = [max(v[k] for v in verts) for k in range(3)]
    with open(os.path.join(HERE, name), "w") as f:
        for line in header:
            f.write("# " + line + "\n")
        f.write("# bounding box min (%.4f, %.4f, %.4f) max (%.4f, %.4f, %.4f); %d vertices, %d triangles\n"
                % (*lo, *hi, len(verts), len(tris)))
        for v in verts:
            f.write("v %.6f %.6f %.6f\n" % v)
        for a, b, c in tris:
            f.write("f %d %d %d\n" % (a + 1, b + 1, c + 1))


def spout():
    """A gooseneck tube swept along a path in the y = 0 plane."""
    r, sides = 0.012, 24
    path = [((0.0, 0.20), (0.0, 1.0))]  # (x, z), unit tangent
    path.append(((0.0, 0.26), (0.0, 1.0)))
    for i in range(1, 13):  # quarter bend up -> +x, centre (0.04, 0.26), radius 0.04
        a = math.pi - i * (math.pi / 2) / 12
        path.append(((0.04 + 0.04 * math.cos(a), 0.26 + 0.04 * math.sin(a)), (math.sin(a), -math.cos(a))))
    path.append(((0.17, 0.30), (1.0, 0.0)))
    for i in range(1, 9):  # quarter bend +x -> down, centre (0.17, 0.27), radius 0.03
        a = math.pi / 2 - i * (math.pi / 2) / 8
        path.append(((0.17 + 0.03 * math.cos(a), 0.27 + 0.03 * math.sin(a)), (math.sin(a), -math.cos(a))))
    path.append(((0.20, 0.25), (0.0, -1.0)))
    verts, tris = [], []
    for (px, pz), (tx, tz) in path:
        nx, nz = tz, -tx  # in-plane normal; the other ring axis is +y
        for s in range(sides):
            t = 2 * math.pi * s / sides
            verts.append((px + r * math.cos(t) * nx, r * math.sin(t), pz + r * math.cos(t) * nz))
    for i in range(len(path) - 1):
        for s in range(sides):
            a, b = i * sides + s, i * sides + (s + 1) % sides
            tris += [(a, b, b + sides), (a, b + sides, a + sides)]
    for ring, centre in ((0, path[0][0]), (len(path) - 1, path[-1][0])):
        c = len(verts)
        verts.append((centre[0], 0.0, centre[1]))
        for s in range(sides):
            a, b = ring * sides + s, ring * sides + (s + 1) % sides
            tris.append((c, b, a) if ring == 0 else (c, a, b))
    header = ["faucet spout: a closed gooseneck tube, radius 0.012 m, object frame (z up).",
              "Centre line: up from (0, 0, 0.20) to (0, 0, 0.26), bends to +x (radius 0.04) at z = 0.30,",
              "runs to x = 0.17, bends down (radius 0.03) to the nozzle, which ends at (0.20, 0, 0.25).",
              "Both ends are capped (closed solid): the inlet disc at z = 0.20 faces -z (it sits on a body),",
              "the outlet disc at z = 0.25 faces -z (water leaves there)."]
    write_obj("faucet_spout.obj", header, verts, tris)


def handle():
    """A flat lever: a hub disc with a tapered bar pointing -x, extruded in z."""
    hub_r, w0, w1, length, thick = 0.015, 0.009, 0.007, 0.09, 0.012
    cx, cy, cz = -0.035, 0.0, 0.215  # hub centre (the lever's hinge point)
    half = lambda x: w0 + (w1 - w0) * (-x) / length  # bar half width at x <= 0
    lo, hi = -length, 0.0  # where the bar edge leaves the hub circle (bisection)
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        if mid * mid + half(mid) ** 2 > hub_r * hub_r:
            lo = mid
        else:
            hi = mid
    jx, jy = lo, half(lo)
    beta = math.atan2(jy, -jx)  # junction angle measured from -x
    outline = []  # counter-clockwise seen from +z; star-shaped about the hub centre
    n_hub = 40
    for i in range(n_hub + 1):  # hub arc through +x, from the lower to the upper junction
        a = -(math.pi - beta) + i * 2 * (math.pi - beta) / n_hub
        outline.append((hub_r * math.cos(a), hub_r * math.sin(a)))
    n_tip = 16
    for i in range(n_tip + 1):  # rounded tip around (-length, 0)
        a = math.pi / 2 + i * math.pi / n_tip
        outline.append((-length + w1 * math.cos(a), w1 * math.sin(a)))
    verts, tris = [], []
    n = len(outline)
    for z in (cz - thick / 2, cz + thick / 2):
        for x, y in outline:
            verts.append((cx + x, cy + y, z))
    bot_c, top_c = len(verts), len(verts) + 1
    verts += [(cx, cy, cz - thick / 2), (cx, cy, cz + thick / 2)]
    for i in range(n):
        j = (i + 1) % n
        tris += [(i, j, n + j), (i, n + j, n + i)]  # side wall
        tris.append((top_c, n + i, n + j))  # top fan
        tris.append((bot_c, j, i))  # bottom fan
    header = ["faucet handle: a closed flat lever 0.012 m thick, object frame (z up).",
              "Hub disc radius 0.015 m centred at (-0.035, 0, 0.215) (the natural hinge point, e.g. axis +y);",
              "a tapered bar (half width 0.009 -> 0.007) runs along -x to a rounded tip at x = -0.132."]
    write_obj("faucet_handle.obj", header, verts, tris)


if __name__ == "__main__":
    spout()
    handle()
