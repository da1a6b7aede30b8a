#!/usr/bin/env python3
"""Writes the two meshes of the distance-field morph example (docs/morph3d.md), made here:
sphere.obj, a UV sphere of radius 1 (genus 0), and torus.obj, a torus about the y axis with ring
radius 1 and tube radius 0.4 (genus 1), both centred at the origin, closed, and wound
counter-clockwise seen from outside.  Usage: make_shapes.py OUT_DIR"""
import math
import sys


def write(path, vertices, triangles, comment):
    with open(path, "w", encoding="ascii") as f:
        f.write(f"# {comment}\n")
        for v in vertices:
            f.write("v %.6f %.6f %.6f\n" % v)
        for t in triangles:
            f.write("f %d %d %d\n" % (t[0] + 1, t[1] + 1, t[2] + 1))


def sphere(rings=32, segments=64):
    v = [(0.0, 1.0, 0.0)]
    for r in range(1, rings):
        theta = math.pi * r / rings
        for s in range(segments):
            phi = 2 * math.pi * s / segments
            v.append((math.sin(theta) * math.cos(phi), math.cos(theta), -math.sin(theta) * math.sin(phi)))
    v.append((0.0, -1.0, 0.0))
    south = len(v) - 1

    def ring(r, s):
        return 1 + (r - 1) * segments + s % segments

    t = [(0, ring(1, s), ring(1, s + 1)) for s in range(segments)]
    for r in range(1, rings - 1):
        for s in range(segments):
            t.append((ring(r, s), ring(r + 1, s), ring(r + 1, s + 1)))
            t.append((ring(r, s), ring(r + 1, s + 1), ring(r, s + 1)))
    t += [(ring(rings - 1, s), south, ring(rings - 1, s + 1)) for s in range(segments)]
    return v, t


def torus(big=1.0, small=0.4, rings=64, sides=32):
    v = []
    for i in range(rings):
        u = 2 * math.pi * i / rings
        for j in range(sides):
            w = 2 * math.pi * j / sides
            d = big + small * math.cos(w)
            v.append((d * math.cos(u), small * math.sin(w), -d * math.sin(u)))

    def at(i, j):
        return (i % rings) * sides + j % sides

    t = []
    for i in range(rings):
        for j in range(sides):
            t.append((at(i, j), at(i + 1, j), at(i + 1, j + 1)))
            t.append((at(i, j), at(i + 1, j + 1), at(i, j + 1)))
    return v, t


if __name__ == "__main__":
    out = sys.argv[1] if len(sys.argv) > 1 else "."
    write(f"{out}/sphere.obj", *sphere(), "a UV sphere of radius 1 (examples/morph3d/make_shapes.py)")
    write(f"{out}/torus.obj", *torus(), "a torus, ring radius 1, tube radius 0.4 (examples/morph3d/make_shapes.py)")
