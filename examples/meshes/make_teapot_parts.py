#!/usr/bin/env python3
"""Writes teapot-parts.obj and teapot-parts.mtl: the Utah teapot (teapot.obj) with one material per
part, so the NPR renderer's hue rules (Rademacher 99, section 3.2.4) can be seen on a real model:
a whitish body (no warm light: cool whites), a purple lid and handle (stronger cool light) and a red
knob and spout (more cool, less warm light).

The parts are found from the geometry alone:
  - the surface splits into connected pieces by shared vertex indices: body with handle, lid,
    knob, spout (the lid, knob and spout are separate patches in Newell's data);
  - inside the body piece, the handle is what sticks out of the body of revolution: a face with a
    vertex farther from the vertical axis than the body is at that vertex's height (the body's
    radius profile is taken from its rings of vertices away from the handle, x > 0 or |z| > 0.6,
    and interpolated between rings), within the handle's width (|z| < 0.4) and behind the axis
    (x < 0).

Usage: python3 examples/meshes/make_teapot_parts.py [OUT_DIR]   (Python standard library only;
writes next to this script by default; a test checks that it regenerates the committed files byte
for byte)
"""
import bisect
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))

MATERIALS = [  # name, Kd (display RGB)
    ("body", (0.95, 0.94, 0.90)),
    ("lid", (0.55, 0.36, 0.78)),
    ("knob", (0.80, 0.12, 0.10)),
    ("handle", (0.55, 0.36, 0.78)),
    ("spout", (0.80, 0.12, 0.10)),
]


def read(path):
    vertices, faces, lines = [], [], []
    with open(path) as f:
        for line in f:
            lines.append(line)
            t = line.split()
            if not t:
                continue
            if t[0] == "v":
                vertices.append(tuple(float(x) for x in t[1:4]))
            elif t[0] == "f":
                faces.append((len(lines) - 1, [int(c.split("/")[0]) - 1 for c in t[1:]]))
    return vertices, faces, lines


def pieces(vertices, faces):
    parent = list(range(len(vertices)))

    def find(a):
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    for _, f in faces:
        for v in f[1:]:
            a, b = find(f[0]), find(v)
            if a != b:
                parent[a] = b
    return [find(f[0]) for _, f in faces]


def centre(vertices, f):
    return tuple(sum(vertices[v][i] for v in f) / len(f) for i in range(3))


def classify(vertices, faces):
    piece = pieces(vertices, faces)
    boxes = {}
    for (_, f), p in zip(faces, piece):
        for v in f:
            x, y, z = vertices[v]
            lo, hi = boxes.get(p, ((x, y, z), (x, y, z)))
            boxes[p] = (tuple(map(min, lo, (x, y, z))), tuple(map(max, hi, (x, y, z))))
    body = max(boxes, key=lambda p: sum(1 for q in piece if q == p))
    spout = max(boxes, key=lambda p: boxes[p][1][0])
    knob = max(boxes, key=lambda p: boxes[p][1][1])
    names = {body: "body", spout: "spout", knob: "knob"}
    for p in boxes:
        names.setdefault(p, "lid")
    # The body of revolution: its vertices lie on rings (one height, one radius each); the rings'
    # radii are measured away from the handle (x > 0 or |z| > 0.6), and the body's radius between
    # two rings is interpolated linearly. (A face-centre test against rings found within a fixed
    # height window missed the rings wherever they lie farther apart than the window, which
    # labelled a saw-toothed band of body faces as handle.)
    ring = {}
    for (_, f), p in zip(faces, piece):
        if p != body:
            continue
        for v in f:
            x, y, z = vertices[v]
            if x > 0 or abs(z) > 0.6:
                ring[y] = max(ring.get(y, 0.0), math.hypot(x, z))
    heights = sorted(ring)

    def body_radius(y):
        i = bisect.bisect_left(heights, y)
        if i < len(heights) and heights[i] == y:
            return ring[y]
        if i == 0 or i == len(heights):
            return 0.0  # above or below the body: nothing of it there
        y0, y1 = heights[i - 1], heights[i]
        return ring[y0] + (ring[y1] - ring[y0]) * (y - y0) / (y1 - y0)

    def off_body(v):
        x, y, z = vertices[v]
        return math.hypot(x, z) > body_radius(y) + 0.01

    out = []
    for (_, f), p in zip(faces, piece):
        name = names[p]
        if p == body:
            # The handle sticks out of the body behind the axis (x < 0), within its width
            # (|z| < 0.4): a face with a vertex off the body of revolution there is the handle's.
            x, y, z = centre(vertices, f)
            if x < 0 and abs(z) < 0.4 and any(off_body(v) for v in f):
                name = "handle"
        out.append(name)
    return out


def main():
    out_dir = sys.argv[1] if len(sys.argv) > 1 else HERE
    vertices, faces, lines = read(os.path.join(HERE, "teapot.obj"))
    names = classify(vertices, faces)
    material_of_line = {line: name for (line, _), name in zip(faces, names)}
    obj = ["# The Utah teapot (teapot.obj, see SOURCES.md) with one material per part.\n",
           "# Written by make_teapot_parts.py; do not edit.\n",
           "mtllib teapot-parts.mtl\n"]
    current = None
    for i, line in enumerate(lines):
        if line.startswith("#"):
            continue
        name = material_of_line.get(i)
        if name is not None and name != current:
            obj.append("usemtl %s\n" % name)
            current = name
        obj.append(line)
    mtl = ["# Materials of teapot-parts.obj, written by make_teapot_parts.py.\n"]
    for name, kd in MATERIALS:
        mtl.append("\nnewmtl %s\nKd %.2f %.2f %.2f\n" % (name, *kd))
    with open(os.path.join(out_dir, "teapot-parts.obj"), "w") as f:
        f.writelines(obj)
    with open(os.path.join(out_dir, "teapot-parts.mtl"), "w") as f:
        f.writelines(mtl)
    counts = {name: names.count(name) for name, _ in MATERIALS}
    print("teapot-parts.obj: " + ", ".join("%s %d" % kv for kv in counts.items()) + " faces")


if __name__ == "__main__":
    main()
