#!/usr/bin/env python3
"""Helpers of studio_test.sh (python3 standard library only): PNG read/write, image checks,
events files, edit scripts and OBJ comparison.

  studio_tool.py drawing OUT.png W H          a drawing: left half red, right half blue
  studio_tool.py events OUT.json W H SPEC...  events file; SPEC = FRAME:TYPE:ARGS (see below)
  studio_tool.py pixel PNG X Y R G B TOL      pixel (X, Y) within TOL of (R, G, B) per channel
  studio_tool.py notpixel PNG X Y R G B TOL   pixel (X, Y) farther than TOL from (R, G, B)
  studio_tool.py compare PNG GOLDEN TOL FRAC  same size, at most FRAC of the pixels differ by > TOL
  studio_tool.py ops MANIFEST KEY OUT.json    `vdg deform` ops of KEY's edit log (one stroke), with
                                              the key camera the manifest saved
  studio_tool.py objclose A.obj B.obj EPS     same vertex count, every coordinate within EPS
  studio_tool.py logcheck MANIFEST KEY DX DY W H   the key's log: one drag, delta_px (DX, DY), image W x H
  studio_tool.py keyframe MANIFEST KEY        prints the key's frame (0 when the manifest has none)
  studio_tool.py eye MANIFEST KEY             prints the key camera's eye as X,Y,Z

SPEC: "3:key_down:2", "3:key_down:S:ctrl", "4:mouse_down:630:300", "5:mouse_move:640:290",
"9:mouse_up:670:275".
"""
import json
import os
import struct
import sys
import zlib


def write_png(path, w, h, rgb_rows):
    raw = b"".join(b"\x00" + bytes(row) for row in rgb_rows)

    def chunk(tag, data):
        c = struct.pack(">I", len(data)) + tag + data
        return c + struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF)

    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
    with open(path, "wb") as f:
        f.write(png)


def read_png(path):
    """Returns (w, h, rows of RGB tuples)."""
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise SystemExit(f"{path}: not a PNG")
    pos, idat, w = 8, b"", 0
    while pos < len(data):
        (n,) = struct.unpack(">I", data[pos:pos + 4])
        tag, body = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + n]
        pos += 12 + n
        if tag == b"IHDR":
            w, h, depth, ctype, _, _, interlace = struct.unpack(">IIBBBBB", body)
            if depth != 8 or ctype not in (2, 6) or interlace:
                raise SystemExit(f"{path}: only 8-bit RGB/RGBA, non-interlaced PNGs")
            bpp = 3 if ctype == 2 else 4
        elif tag == b"IDAT":
            idat += body
    raw = zlib.decompress(idat)
    stride = w * bpp
    rows, prev = [], bytearray(stride)
    for y in range(h):
        ftype = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b = prev[i]
            c = prev[i - bpp] if i >= bpp else 0
            if ftype == 1:
                line[i] = (line[i] + a) & 255
            elif ftype == 2:
                line[i] = (line[i] + b) & 255
            elif ftype == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif ftype == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                pred = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                line[i] = (line[i] + pred) & 255
        rows.append([tuple(line[x * bpp:x * bpp + 3]) for x in range(w)])
        prev = line
    return w, h, rows


def fail(msg):
    print("studio_tool: " + msg, file=sys.stderr)
    sys.exit(1)


def events(out, w, h, specs):
    evs = []
    for spec in specs:
        parts = spec.split(":")
        frame, kind = int(parts[0]), parts[1]
        e = {"frame": frame, "type": kind}
        if kind in ("key_down", "key_up"):
            e["key"] = parts[2]
            if len(parts) > 3:
                e["mods"] = parts[3].split("+")
        elif kind in ("mouse_down", "mouse_up"):
            e["button"] = "left"
            e["x"], e["y"] = float(parts[2]), float(parts[3])
        elif kind == "mouse_move":
            e["x"], e["y"] = float(parts[2]), float(parts[3])
        elif kind == "scroll":
            e["x"], e["y"], e["dx"], e["dy"] = (float(v) for v in parts[2:6])
        evs.append(e)
    with open(out, "w") as f:
        json.dump({"version": 1, "window": [w, h], "events": evs}, f, indent=1)


def key_entry(manifest, key):
    m = json.load(open(manifest))
    for k in m["keys"]:
        if k.get("name") == key:
            return m, k
    fail(f"{manifest}: no key '{key}'")


def edit_log(manifest, key):
    _, k = key_entry(manifest, key)
    mesh = os.path.join(os.path.dirname(manifest), k["mesh"])
    return json.load(open(mesh[:-4] + ".edits.json")), k


def main(argv):
    cmd = argv[1]
    if cmd == "drawing":
        out, w, h = argv[2], int(argv[3]), int(argv[4])
        rows = [[c for x in range(w) for c in ((220, 40, 40) if x < w // 2 else (40, 60, 220))] for _ in range(h)]
        write_png(out, w, h, rows)
    elif cmd == "events":
        events(argv[2], int(argv[3]), int(argv[4]), argv[5:])
    elif cmd in ("pixel", "notpixel"):
        w, h, rows = read_png(argv[2])
        x, y = int(argv[3]), int(argv[4])
        want = tuple(int(v) for v in argv[5:8])
        tol = int(argv[8])
        got = rows[y][x]
        close = all(abs(a - b) <= tol for a, b in zip(got, want))
        if close != (cmd == "pixel"):
            fail(f"{argv[2]}: pixel ({x}, {y}) is {got}, expected {'' if cmd == 'pixel' else 'not '}{want} +- {tol}")
    elif cmd == "compare":
        w, h, a = read_png(argv[2])
        gw, gh, b = read_png(argv[3])
        tol, frac = int(argv[4]), float(argv[5])
        if (w, h) != (gw, gh):
            fail(f"{argv[2]} is {w}x{h}, the golden {argv[3]} is {gw}x{gh}")
        bad = sum(1 for y in range(h) for x in range(w) if max(abs(p - q) for p, q in zip(a[y][x], b[y][x])) > tol)
        if bad > frac * w * h:
            fail(f"{argv[2]}: {bad} of {w * h} pixels differ from {argv[3]} by more than {tol}")
        print(f"{argv[2]}: {bad} of {w * h} pixels differ from the golden by more than {tol}")
    elif cmd == "logcheck":
        log, _ = edit_log(argv[2], argv[3])
        entries = log["entries"]
        if len(entries) != 1 or len(entries[0]["ops"]) != 1:
            fail(f"key {argv[3]}: expected one stroke of one op, got {json.dumps(entries)[:300]}")
        e, op = entries[0], entries[0]["ops"][0]
        want = [float(argv[4]), float(argv[5])]
        if op["op"] != "drag" or [float(v) for v in op["delta_px"]] != want:
            fail(f"key {argv[3]}: expected a drag by {want} px, got {json.dumps(op)}")
        if list(e.get("image_size", [])) != [int(argv[6]), int(argv[7])]:
            fail(f"key {argv[3]}: expected image_size [{argv[6]}, {argv[7]}], got {e.get('image_size')}")
    elif cmd == "keyframe":
        print(key_entry(argv[2], argv[3])[1].get("frame", 0))
    elif cmd == "eye":
        k = key_entry(argv[2], argv[3])[1]
        if "camera" not in k:
            fail(f"{argv[2]}: key {argv[3]} has no camera")
        print(",".join(repr(float(v)) for v in k["camera"]["eye"]))
    elif cmd == "ops":
        log, k = edit_log(argv[2], argv[3])
        if "camera" not in k:
            fail(f"{argv[2]}: key {argv[3]} has no camera")
        entry = log["entries"][0]
        script = {"version": 1, "camera": k["camera"], "image_size": entry["image_size"], "ops": entry["ops"]}
        with open(argv[4], "w") as f:
            json.dump(script, f, indent=1)
    elif cmd == "objclose":
        def verts(p):
            return [tuple(float(v) for v in l.split()[1:4]) for l in open(p) if l.startswith("v ")]

        a, b, eps = verts(argv[2]), verts(argv[3]), float(argv[4])
        if len(a) != len(b):
            fail(f"{argv[2]} has {len(a)} vertices, {argv[3]} {len(b)}")
        worst = max((abs(p - q) for va, vb in zip(a, b) for p, q in zip(va, vb)), default=0.0)
        if worst > eps:
            fail(f"{argv[2]} and {argv[3]} differ by {worst} (> {eps})")
        moved = 0
        print(f"{argv[2]} = {argv[3]} within {worst:.3g}")
    else:
        fail("unknown command " + cmd)


if __name__ == "__main__":
    main(sys.argv)
