#!/usr/bin/env python3
"""Writes teapot-parts.obj and teapot-parts.mtl: the Utah teapot (teapot.obj) with one material per
part, so the NPR renderer's hue rules (Rademacher 99, section 3.2.4) can be seen on a real model:
a whitish body (no warm light: cool whites), a purple lid and handle (stronger cool light) and a red
knob and spout (more cool, less warm light).

The parts are found from the geometry alone:
  - the surface splits into connected pieces by shared vertex indices: body with handle, lid,
    knob, spout (the lid, knob and spout are separate patches in Newell's data);
  - inside the body piece, the handle is what sticks out of the body of revolution: a face whose
    centre lies farther from the vertical axis than the body does at that height (the body's
    radius profile is measured away from the handle's plane, |z| > 0.6), within the handle's
    width (|z| < 0.4) and behind the axis (x < 0).

Usage: python3 examples/meshes/make_teapot_parts.py [OUT_DIR]   (Python standard library only;
writes next to this script by default; a test checks that it regenerates the committed files byte
for byte)
"""
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
    # The body's radius at each height, away from the handle's plane.
    step = 0.02
    profile = {}
    for (_, f), p in zip(faces, piece):
        if p != body:
            continue
        for v in f:
            x, y, z = vertices[v]
            if abs(z) > 0.6:
                k = int(y / step)
                profile[k] = max(profile.get(k, 0.0), math.hypot(x, z))
    out = []
    for (_, f), p in zip(faces, piece):
        name = names[p]
        if p == body:
            x, y, z = centre(vertices, f)
            k = int(y / step)
            body_r = max(profile.get(k + d, 0.0) for d in (-1, 0, 1))
            if x < 0 and abs(z) < 0.4 and math.hypot(x, z) > body_r + 0.01:
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
