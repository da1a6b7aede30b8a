#!/usr/bin/env python3
"""Draws the two faces of the 2D morph example (docs/morph.md), byte-identical on every run.

    python3 make_faces.py [OUT_DIR]      (default: the folder of this script)

Writes OUT_DIR/face_a.png and OUT_DIR/face_b.png, 200 x 200 RGBA (python3 standard library only:
zlib for the PNG stream). Face A is round and warm-coloured with its eyes at (75, 90) and
(125, 90) and its mouth at y = 135; face B is a tall oval, cooler, eyes at (80, 80) and (120, 80),
mouth at y = 148. grid.json and lines.json in this folder mark the same features on both.
Every shape is drawn anti-aliased from its signed distance (coverage = clamp(0.5 - d, 0, 1)).

    python3 make_faces.py --sequences OUT_DIR

writes two animated sequences instead (Parent 4.10, morphing two animated sequences):
OUT_DIR/seq_a/frame_0000.png ... frame_0007.png, face A swaying left and right, and OUT_DIR/seq_b/,
face B bobbing up and down, plus OUT_DIR/seq_grid.json, grid.json's grids at key frames 0, 2, 4, 6
and 7, each moved with its face (the grid points inside the image follow the face; those on the
image's border slide along it). The frames between the keys get their grids from `vdg morph`'s
Catmull-Rom interpolation of the keys.

Also writes OUT_DIR/drawings.json, the key drawings of `vdg morph --drawings` (Parent 4.5): the
same face as line drawings at three keys (round and smiling, tall and frowning, wide and
laughing), its outline drawn with a different number of points in each key (so the inbetweener
resamples it by arc length).
"""

import json

import math
import os
import struct
import sys
import zlib

kSize = 200

# name: face centre, radii (x, y), skin, eye centres, eye radius, mouth centre y, mouth half-width,
# mouth curve (pixels the corners rise), nose length, background top and bottom colours, hair colour
kFaces = {
    "face_a": dict(centre=(100, 105), radii=(70, 70), skin=(238, 190, 150), eyes=((75, 90), (125, 90)),
                   eye_r=9, mouth_y=135, mouth_w=22, smile=8, nose=(95, 118), sky=((120, 170, 220), (230, 240, 250)),
                   hair=(90, 55, 30)),
    "face_b": dict(centre=(100, 100), radii=(55, 80), skin=(150, 200, 170), eyes=((80, 80), (120, 80)),
                   eye_r=7, mouth_y=148, mouth_w=18, smile=-4, nose=(88, 128), sky=((240, 200, 120), (250, 240, 220)),
                   hair=(40, 40, 90)),
}


def ellipse_distance(x, y, c, r):
    """Approximate signed distance to an axis-aligned ellipse (exact for a circle)."""
    dx, dy = (x - c[0]) / r[0], (y - c[1]) / r[1]
    k = math.hypot(dx, dy)
    return (k - 1.0) * min(r)


def segment_distance(x, y, a, b):
    ax, ay = a
    bx, by = b
    vx, vy = bx - ax, by - ay
    u = max(0.0, min(1.0, ((x - ax) * vx + (y - ay) * vy) / (vx * vx + vy * vy)))
    return math.hypot(x - ax - u * vx, y - ay - u * vy)


def mouth_distance(x, y, f):
    """Distance to the mouth: a parabola y = mouth_y - smile * (1 - (dx / w)^2) for |dx| <= w, sampled."""
    cx = f["centre"][0]
    w, my, s = f["mouth_w"], f["mouth_y"], f["smile"]
    pts = [(cx + w * (i / 8.0 - 1.0), my + s * (1.0 - (i / 8.0 - 1.0) ** 2) - s) for i in range(17)]
    return min(segment_distance(x, y, pts[i], pts[i + 1]) for i in range(16))


def cover(d):
    return max(0.0, min(1.0, 0.5 - d))


def over(dst, colour, alpha):
    return tuple(dst[i] * (1.0 - alpha) + colour[i] * alpha for i in range(3))


def draw(f):
    rows = []
    for y in range(kSize):
        row = bytearray()
        for x in range(kSize):
            px, py = x + 0.5, y + 0.5
            top, bottom = f["sky"]
            s = py / kSize
            c = tuple(top[i] * (1 - s) + bottom[i] * s for i in range(3))
            cx, cy = f["centre"]
            rx, ry = f["radii"]
            # hair: a larger ellipse behind the top of the head
            hair = ellipse_distance(px, py, (cx, cy - 8), (rx + 8, ry + 6))
            if py < cy:
                c = over(c, f["hair"], cover(hair))
            c = over(c, f["skin"], cover(ellipse_distance(px, py, f["centre"], f["radii"])))
            for e in f["eyes"]:
                c = over(c, (250, 250, 250), cover(ellipse_distance(px, py, e, (f["eye_r"] * 1.5, f["eye_r"]))))
                c = over(c, (30, 30, 40), cover(ellipse_distance(px, py, e, (f["eye_r"] * 0.6, f["eye_r"] * 0.6))))
            c = over(c, (120, 60, 50), cover(segment_distance(px, py, (cx, f["nose"][0]), (cx, f["nose"][1])) - 2.0))
            c = over(c, (170, 40, 50), cover(mouth_distance(px, py, f) - 3.0))
            row += bytes(int(round(v)) for v in c) + b"\xff"
        rows.append(bytes(row))
    return rows


def png(rows):
    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    raw = b"".join(b"\x00" + r for r in rows)
    header = struct.pack(">IIBBBBB", kSize, kSize, 8, 6, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")


def outline(c, r, n):
    """n + 1 points round an ellipse from the top, clockwise on screen (closed: last = first)."""
    return [[round(c[0] + r[0] * math.sin(2 * math.pi * i / n), 2), round(c[1] - r[1] * math.cos(2 * math.pi * i / n), 2)]
            for i in range(n + 1)]


def mouth(cx, y, w, rise, n):
    return [[round(cx + w * (2.0 * i / (n - 1) - 1.0), 2), round(y - rise * (2.0 * i / (n - 1) - 1.0) ** 2, 2)]
            for i in range(n)]


def drawings():
    keys = []
    for time, c, r, n, eye_y, eye_dx, mouth_y, mouth_w, rise, mouth_n in (
            (0, (100, 105), (70, 70), 24, 90, 25, 130, 22, 8, 9),
            (1, (100, 100), (55, 80), 40, 80, 20, 150, 18, -5, 5),
            (2, (100, 110), (80, 62), 32, 95, 28, 135, 30, 12, 9)):
        eyes = [[[100 - eye_dx - 6, eye_y], [100 - eye_dx + 6, eye_y]], [[100 + eye_dx - 6, eye_y], [100 + eye_dx + 6, eye_y]]]
        keys.append({"time": time, "strokes": [outline(c, r, n), mouth(100, mouth_y, mouth_w, rise, mouth_n)] + eyes})
    doc = {"version": 1, "curve": "catmull-rom", "width": 200, "height": 200, "keys": keys}
    text = json.dumps(doc, indent=None, separators=(", ", ": "))
    return text.replace(', {"time"', ',\n  {"time"').replace('"keys": [{', '"keys": [\n  {') + "\n"


kSequenceFrames = 8
kSequenceKeys = (0, 2, 4, 6, 7)


def sway(name, i):
    """The face's offset (dx, dy) in frame i of its sequence: A sways sideways, B bobs."""
    phase = 2.0 * math.pi * i / kSequenceFrames
    return (round(12.0 * math.sin(phase), 3), 0.0) if name == "face_a" else (0.0, round(-9.0 * math.sin(phase), 3))


def moved(face, d):
    """The face dict with every position moved by d (the nose and mouth by their rows only)."""
    dx, dy = d
    f = dict(face)
    f["centre"] = (face["centre"][0] + dx, face["centre"][1] + dy)
    f["eyes"] = tuple((x + dx, y + dy) for x, y in face["eyes"])
    f["nose"] = (face["nose"][0] + dy, face["nose"][1] + dy)
    f["mouth_y"] = face["mouth_y"] + dy
    return f


def moved_points(points, d):
    """Grid points moved by d; those on the image's border stay on it (they slide along it)."""
    out = []
    for x, y in points:
        nx = x if x in (0, kSize) else x + d[0]
        ny = y if y in (0, kSize) else y + d[1]
        out.append([round(nx, 3), round(ny, 3)])
    return out


def sequences(out):
    here = os.path.dirname(os.path.abspath(__file__))
    with open(os.path.join(here, "grid.json")) as f:
        grid = json.load(f)
    for name, folder in (("face_a", "seq_a"), ("face_b", "seq_b")):
        os.makedirs(os.path.join(out, folder), exist_ok=True)
        for i in range(kSequenceFrames):
            with open(os.path.join(out, folder, "frame_%04d.png" % i), "wb") as f:
                f.write(png(draw(moved(kFaces[name], sway(name, i)))))
    keys = [{"frame": i, "src": moved_points(grid["src"], sway("face_a", i)),
             "dst": moved_points(grid["dst"], sway("face_b", i))} for i in kSequenceKeys]
    doc = {"version": 1, "rows": grid["rows"], "cols": grid["cols"], "keys": keys}
    with open(os.path.join(out, "seq_grid.json"), "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")


def main():
    if len(sys.argv) > 2 and sys.argv[1] == "--sequences":
        sequences(sys.argv[2])
        return
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "drawings.json"), "w") as f:
        f.write(drawings())
    for name, face in kFaces.items():
        with open(os.path.join(out, name + ".png"), "wb") as f:
            f.write(png(draw(face)))


if __name__ == "__main__":
    main()
