#!/usr/bin/env python3
"""Generates the walking character of Rademacher 99, section 4.3 (Figures 8-12), reproducibly.

    python3 make_walker.py [OUT_DIR]      (default: the folder of this script)

Writes, byte-identical on every run (python3 standard library only):
  walker.glb            a skinned humanoid (13 joints, linear blend skinning, inverse bind matrices)
                        with one looping walk cycle: 40 frames at 24 fps, LINEAR samplers, 41
                        samples whose last equals the first. Y up, facing +Z, walking in place,
                        about 1.8 units tall, feet on y = 0 at rest and in the cycle.
  base_f10.obj, base_f30.obj
                        the skinned mesh at frames 10 and 30, posed here from the same float32
                        data that walker.glb holds (an independent check of a glTF evaluator).
  keys/{front,side}_f{10,30}.obj
                        the four key deformations of section 4.3: the same mesh (same vertex order
                        and triangles as walker.glb; only v and f lines) posed at that frame with
                        the arm and leg swing exaggerated. Side view: the swing seen from the side
                        is multiplied (kSideSwing). Front view: arms and legs spread outward
                        (kFrontSpread*), with a little more swing.
  walker.vdg.json, walker-world.vdg.json
                        manifests (version 2) with the glTF base and the four keys; offsets carried
                        in the skinning frames ("skinned") or in world space ("world", the paper's).

Units: metres, radians inside (degrees in the tables), seconds for glTF time. The walk is a
function of the phase p = 2 pi frame / 40: the left leg is furthest forward at frame 10 and the
right leg at frame 30, the extremes the paper's key deformations exaggerate.
"""

import json
import math
import os
import struct
import sys

kFrames = 40  # frames in the cycle (section 4.3)
kFps = 24.0
kKeyFrames = (10, 30)

# Exaggeration of the key deformations (section 4.3: "making the arms and legs swing out more").
kSideSwing = 1.8  # side view: thigh and upper-arm swing multiplied
kSideBend = 1.4  # side view: knee and elbow bend multiplied
kFrontSwing = 1.3  # front view: swing multiplied a little
kFrontSpreadArmDeg = 28.0  # front view: arms raised sideways (abduction)
kFrontSpreadLegDeg = 9.0  # front view: legs spread sideways

# Walk cycle amplitudes, degrees.
kThighSwingDeg = 24.0
kArmSwingDeg = 20.0
kHipTwistDeg = 6.0

# ---------------------------------------------------------------------------------------------
# Small vector, quaternion and matrix helpers (tuples; matrices are row-major 4x4 lists).


def f32(x):
    return struct.unpack("<f", struct.pack("<f", x))[0]


def add(a, b):
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def scale(a, s):
    return (a[0] * s, a[1] * s, a[2] * s)


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def normalize(a):
    n = math.sqrt(dot(a, a))
    return scale(a, 1.0 / n)


def lerp(a, b, t):
    return a + (b - a) * t


def smoothstep(e0, e1, x):
    t = min(1.0, max(0.0, (x - e0) / (e1 - e0)))
    return t * t * (3.0 - 2.0 * t)


def quat_axis_angle(axis, angle):
    """Unit quaternion (x, y, z, w), glTF order."""
    s = math.sin(angle / 2.0)
    return (axis[0] * s, axis[1] * s, axis[2] * s, math.cos(angle / 2.0))


def quat_mul(a, b):
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw,
            aw * bw - ax * bx - ay * by - az * bz)


def quat_f32(q):
    """The quaternion as glTF stores it: normalised, then rounded to float32."""
    n = math.sqrt(sum(c * c for c in q))
    return tuple(f32(c / n) for c in q)


def mat_trs(t, q):
    x, y, z, w = q
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w), t[0]],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w), t[1]],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y), t[2]],
            [0.0, 0.0, 0.0, 1.0]]


def mat_mul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def mat_point(m, p):
    return tuple(m[i][0] * p[0] + m[i][1] * p[1] + m[i][2] * p[2] + m[i][3] for i in range(3))


kX = (1.0, 0.0, 0.0)
kY = (0.0, 1.0, 0.0)
kZ = (0.0, 0.0, 1.0)
kIdentityQuat = (0.0, 0.0, 0.0, 1.0)

# ---------------------------------------------------------------------------------------------
# Skeleton: name, parent index, rest position in world space (rest rotations are identity, so the
# inverse bind matrix of a joint is a translation by minus its rest position). The character's
# left is +X (it faces +Z, Y up).

kJoints = [
    ("hips", -1, (0.0, 0.92, 0.0)),
    ("spine", 0, (0.0, 1.05, 0.0)),
    ("head", 1, (0.0, 1.53, 0.0)),
    ("upperarm_L", 1, (0.215, 1.43, 0.0)),
    ("forearm_L", 3, (0.235, 1.15, 0.0)),
    ("upperarm_R", 1, (-0.215, 1.43, 0.0)),
    ("forearm_R", 5, (-0.235, 1.15, 0.0)),
    ("thigh_L", 0, (0.095, 0.90, 0.0)),
    ("shin_L", 7, (0.095, 0.48, 0.012)),
    ("foot_L", 8, (0.095, 0.085, 0.0)),
    ("thigh_R", 0, (-0.095, 0.90, 0.0)),
    ("shin_R", 10, (-0.095, 0.48, 0.012)),
    ("foot_R", 11, (-0.095, 0.085, 0.0)),
]
kJointIndex = {name: i for i, (name, _, _) in enumerate(kJoints)}


def joint_rest_local(j):
    name, parent, pos = kJoints[j]
    if parent < 0:
        return pos
    return sub(pos, kJoints[parent][2])


# ---------------------------------------------------------------------------------------------
# Mesh: each body part is a closed tube (rings of vertices around a centre line, a pole at each
# end), so limbs bend smoothly at the joints they span. Parts overlap where they meet, as in a
# simple game character.


class MeshBuilder:
    def __init__(self):
        self.positions = []
        self.weights = []  # per vertex: list of (joint, weight)
        self.triangles = []

    def tube(self, stations, segments, side_hint):
        """stations: list of (centre, radius_u, radius_v, weights, direction); the first and last
        have radius 0 and become poles. side_hint: a vector not along the tube, giving u."""
        first = len(self.positions)
        ring_starts = []
        for centre, ru, rv, weights, direction in stations:
            if ru == 0.0 and rv == 0.0:
                ring_starts.append(len(self.positions))
                self.positions.append(centre)
                self.weights.append(weights)
                continue
            d = normalize(direction)
            u = normalize(sub(side_hint, scale(d, dot(side_hint, d))))
            v = cross(d, u)
            ring_starts.append(len(self.positions))
            for k in range(segments):
                t = 2.0 * math.pi * k / segments
                offset = add(scale(u, ru * math.cos(t)), scale(v, rv * math.sin(t)))
                self.positions.append(add(centre, offset))
                self.weights.append(weights)
        tris = []
        n = len(stations)
        for i in range(n - 1):
            a_pole = stations[i][1] == 0.0 and stations[i][2] == 0.0
            b_pole = stations[i + 1][1] == 0.0 and stations[i + 1][2] == 0.0
            a, b = ring_starts[i], ring_starts[i + 1]
            for k in range(segments):
                k1 = (k + 1) % segments
                if a_pole:
                    tris.append((a, b + k1, b + k))
                elif b_pole:
                    tris.append((a + k, a + k1, b))
                else:
                    tris.append((a + k, a + k1, b + k1))
                    tris.append((a + k, b + k1, b + k))
        # Orient outward: the signed volume of a closed part must be positive.
        volume = sum(dot(self.positions[i], cross(self.positions[j], self.positions[k]))
                     for i, j, k in tris)
        if volume < 0.0:
            tris = [(i, k, j) for i, j, k in tris]
        self.triangles.extend(tris)
        return first


def capsule_stations(path, radii, start_cap, end_cap, weight_fn, step):
    """Stations along a polyline. path: points; radii(s) -> (ru, rv) at arc length s along it;
    start_cap / end_cap: how far the rounded caps reach beyond the ends; weight_fn(s) -> weights."""
    lengths = [0.0]
    for a, b in zip(path, path[1:]):
        lengths.append(lengths[-1] + math.sqrt(dot(sub(b, a), sub(b, a))))
    total = lengths[-1]

    def at(s):
        s_clamped = min(max(s, 0.0), total)
        for i in range(len(path) - 1):
            if s_clamped <= lengths[i + 1] or i == len(path) - 2:
                t = (s_clamped - lengths[i]) / (lengths[i + 1] - lengths[i])
                direction = sub(path[i + 1], path[i])
                point = add(path[i], scale(direction, t))
                # Beyond the ends, continue along the end segments.
                if s < 0.0:
                    point = add(point, scale(normalize(direction), s))
                elif s > total:
                    point = add(point, scale(normalize(direction), s - total))
                return point, direction
        raise AssertionError

    stations = []
    # Start cap: quarter-circle profile over start_cap, 5 rings, then the body, then the end cap.
    cap_rings = 5
    direction0 = at(0.0)[1]
    point0 = at(-start_cap)[0]
    stations.append((point0, 0.0, 0.0, weight_fn(-start_cap), direction0))
    ru0, rv0 = radii(0.0)
    for i in range(1, cap_rings + 1):
        angle = 0.5 * math.pi * i / (cap_rings + 1)
        s = -start_cap * math.cos(angle)
        f = math.sin(angle)
        point, direction = at(s)
        stations.append((point, ru0 * f, rv0 * f, weight_fn(s), direction))
    body_rings = max(2, int(round(total / step)))
    for i in range(body_rings + 1):
        s = total * i / body_rings
        point, direction = at(s)
        ru, rv = radii(s)
        stations.append((point, ru, rv, weight_fn(s), direction))
    ru1, rv1 = radii(total)
    for i in range(cap_rings, 0, -1):
        angle = 0.5 * math.pi * i / (cap_rings + 1)
        s = total + end_cap * math.cos(angle)
        f = math.sin(angle)
        point, direction = at(s)
        stations.append((point, ru1 * f, rv1 * f, weight_fn(s), direction))
    point1, direction1 = at(total + end_cap)
    stations.append((point1, 0.0, 0.0, weight_fn(total + end_cap), direction1))
    return stations


def table(points):
    """Piecewise-linear function through (x, value-tuple) points, clamped at the ends."""

    def f(x):
        if x <= points[0][0]:
            return points[0][1]
        for (x0, v0), (x1, v1) in zip(points, points[1:]):
            if x <= x1:
                t = (x - x0) / (x1 - x0)
                return tuple(lerp(a, b, t) for a, b in zip(v0, v1))
        return points[-1][1]

    return f


def blend(j0, j1, t):
    """Weights moving from joint j0 (t = 0) to j1 (t = 1)."""
    if t <= 0.0:
        return [(j0, 1.0)]
    if t >= 1.0:
        return [(j1, 1.0)]
    return [(j0, 1.0 - t), (j1, t)]


def build_mesh():
    mb = MeshBuilder()
    J = kJointIndex

    # Torso, from the crotch up to the neck, elliptical sections (half-width, half-depth, z shift).
    torso_profile = table([
        (0.00, (0.120, 0.085)), (0.06, (0.160, 0.105)), (0.14, (0.168, 0.110)),
        (0.22, (0.150, 0.100)), (0.30, (0.140, 0.095)), (0.38, (0.155, 0.102)),
        (0.46, (0.178, 0.112)), (0.54, (0.190, 0.114)), (0.60, (0.192, 0.108)),
        (0.64, (0.170, 0.095)), (0.68, (0.100, 0.070)), (0.71, (0.055, 0.052)),
        (0.80, (0.052, 0.050))])
    torso_bottom = 0.84

    def torso_weights(s):
        y = torso_bottom + s
        if y > 1.50:
            return blend(J["spine"], J["head"], smoothstep(1.50, 1.58, y))
        return blend(J["hips"], J["spine"], smoothstep(0.98, 1.12, y))

    mb.tube(capsule_stations([(0.0, torso_bottom, 0.0), (0.0, torso_bottom + 0.80, 0.0)],
                             torso_profile, 0.07, 0.03, torso_weights, 0.03), 24, kX)

    # Head: an ellipsoid with a nose, so the facing direction reads.
    head_centre = (0.0, 1.695, 0.005)
    hr = (0.092, 0.118, 0.104)

    head_first = len(mb.positions)
    lat_rings = 14
    head_stations = [((head_centre[0], head_centre[1] - hr[1], head_centre[2]), 0.0, 0.0,
                      [(J["head"], 1.0)], kY)]
    for i in range(1, lat_rings):
        theta = math.pi * i / lat_rings
        y = head_centre[1] - hr[1] * math.cos(theta)
        f = math.sin(theta)
        head_stations.append(((head_centre[0], y, head_centre[2]), hr[0] * f, hr[2] * f,
                              [(J["head"], 1.0)], kY))
    head_stations.append(((head_centre[0], head_centre[1] + hr[1], head_centre[2]), 0.0, 0.0,
                          [(J["head"], 1.0)], kY))
    mb.tube(head_stations, 24, kX)
    # The nose: push the front of the face out around (0, 1.68, front).
    for i in range(head_first, len(mb.positions)):
        x, y, z = mb.positions[i]
        if z > head_centre[2]:
            bump = 0.028 * math.exp(-((x / 0.03) ** 2) - ((y - 1.675) / 0.035) ** 2)
            mb.positions[i] = (x, y, z + bump)

    # Arms: shoulder ball, upper arm, elbow, forearm, a flattened hand.
    for side, sign in (("L", 1.0), ("R", -1.0)):
        shoulder = kJoints[J["upperarm_" + side]][2]
        elbow = kJoints[J["forearm_" + side]][2]
        wrist = (sign * 0.250, 0.905, 0.0)
        tip = (sign * 0.258, 0.770, 0.0)
        upper_len = math.sqrt(dot(sub(elbow, shoulder), sub(elbow, shoulder)))
        fore_len = math.sqrt(dot(sub(wrist, elbow), sub(wrist, elbow)))
        e, w = upper_len, upper_len + fore_len
        # radius across (u = the body's side direction) and front-back (v)
        arm_profile = table([(0.0, (0.056, 0.058)), (0.10, (0.050, 0.052)), (e - 0.02, (0.040, 0.042)),
                             (e + 0.04, (0.041, 0.043)), (w - 0.02, (0.030, 0.034)),
                             (w + 0.02, (0.020, 0.040)), (w + 0.07, (0.020, 0.046)),
                             (w + 0.12, (0.016, 0.036))])

        def arm_weights(s, e=e, side=side):
            return blend(J["upperarm_" + side], J["forearm_" + side], smoothstep(e - 0.05, e + 0.05, s))

        mb.tube(capsule_stations([shoulder, elbow, wrist, tip], arm_profile, 0.058, 0.02,
                                 arm_weights, 0.03), 16, kX)

    # Legs: hip ball, thigh, knee, calf, ankle; the feet are separate tubes along +Z.
    for side, sign in (("L", 1.0), ("R", -1.0)):
        hip = kJoints[J["thigh_" + side]][2]
        knee = kJoints[J["shin_" + side]][2]
        ankle = kJoints[J["foot_" + side]][2]
        k = math.sqrt(dot(sub(knee, hip), sub(knee, hip)))
        a = k + math.sqrt(dot(sub(ankle, knee), sub(ankle, knee)))
        leg_profile = table([(0.0, (0.086, 0.088)), (0.12, (0.078, 0.082)), (k - 0.04, (0.054, 0.058)),
                             (k + 0.08, (0.056, 0.062)), (k + 0.16, (0.052, 0.056)),
                             (a - 0.06, (0.038, 0.040)), (a, (0.036, 0.038))])

        def leg_weights(s, k=k, a=a, side=side):
            if s > k + 0.10:
                return blend(J["shin_" + side], J["foot_" + side], smoothstep(a - 0.06, a + 0.01, s))
            return blend(J["thigh_" + side], J["shin_" + side], smoothstep(k - 0.06, k + 0.06, s))

        mb.tube(capsule_stations([hip, knee, ankle], leg_profile, 0.086, 0.036, leg_weights, 0.03),
                16, kX)

        foot_y = 0.046
        heel = (sign * 0.095, foot_y, -0.035)
        toe = (sign * 0.097, foot_y - 0.004, 0.150)
        foot_profile = table([(0.0, (0.044, 0.040)), (0.08, (0.046, 0.046)), (0.185, (0.030, 0.044))])  # (height, half-width)

        def foot_weights(s, side=side):
            return [(J["foot_" + side], 1.0)]

        foot_first = mb.tube(capsule_stations([heel, toe], foot_profile, 0.035, 0.035, foot_weights, 0.03),
                             12, kY)
        # The sole rests on y = 0 exactly.
        lowest = min(p[1] for p in mb.positions[foot_first:])
        for i in range(foot_first, len(mb.positions)):
            x, y, z = mb.positions[i]
            mb.positions[i] = (x, y - lowest, z)

    return mb


# ---------------------------------------------------------------------------------------------
# Walk cycle: local rotations (and the root translation) as functions of the phase.


def walk_angles(p, swing=1.0, bend=1.0, arm_spread=0.0, leg_spread=0.0):
    """Joint angles (radians) at phase p. Positive swing = limb forward (+Z). The multipliers and
    spreads are the key deformations' exaggerations (1, 0 for the base walk)."""
    r = math.radians
    angles = {}
    for side, phase, sign in (("L", p, 1.0), ("R", p + math.pi, -1.0)):
        thigh = swing * r(kThighSwingDeg) * math.sin(phase)
        c = math.cos(phase)
        knee = bend * (r(4.0) + r(55.0) * max(0.0, c) ** 2 + r(10.0) * max(0.0, -c) ** 2)
        foot = thigh - knee - r(8.0) * math.sin(phase)
        angles["thigh_" + side] = (thigh, sign * leg_spread)
        angles["shin_" + side] = knee
        angles["foot_" + side] = foot
        arm = swing * r(kArmSwingDeg) * math.sin(phase + math.pi)
        elbow = bend * (r(10.0) + r(22.0) * 0.5 * (1.0 + math.sin(phase + math.pi)))
        angles["upperarm_" + side] = (arm, sign * arm_spread)
        angles["forearm_" + side] = elbow
    twist = -r(kHipTwistDeg) * math.sin(p)
    angles["hips"] = twist
    angles["spine"] = -1.4 * twist
    angles["head"] = 0.4 * twist
    return angles


def local_rotations(angles):
    """Local quaternions per joint (rest rotations are identity)."""
    q = [kIdentityQuat] * len(kJoints)
    J = kJointIndex
    q[J["hips"]] = quat_axis_angle(kY, angles["hips"])
    q[J["spine"]] = quat_axis_angle(kY, angles["spine"])
    q[J["head"]] = quat_axis_angle(kY, angles["head"])
    for side in ("L", "R"):
        for limb in ("thigh_", "upperarm_"):
            swing, spread = angles[limb + side]
            # Swing forward about -X (down turns towards +Z), then spread sideways about Z.
            q[J[limb + side]] = quat_mul(quat_axis_angle(kZ, spread), quat_axis_angle(kX, -swing))
        q[J["shin_" + side]] = quat_axis_angle(kX, angles["shin_" + side])  # heel goes back
        q[J["forearm_" + side]] = quat_axis_angle(kX, -angles["forearm_" + side])  # hand forward
        q[J["foot_" + side]] = quat_axis_angle(kX, angles["foot_" + side])  # toes down
    return [quat_f32(x) for x in q]


def joint_worlds(rotations, root_translation):
    worlds = []
    for j, (_, parent, _) in enumerate(kJoints):
        t = root_translation if parent < 0 else joint_rest_local(j)
        local = mat_trs(t, rotations[j])
        worlds.append(local if parent < 0 else mat_mul(worlds[parent], local))
    return worlds


def skin_positions(rest, weights, ibms, rotations, root_translation, indices=None):
    worlds = joint_worlds(rotations, root_translation)
    skins = [mat_mul(w, ibm) for w, ibm in zip(worlds, ibms)]
    out = []
    for i in (range(len(rest)) if indices is None else indices):
        p = (0.0, 0.0, 0.0)
        for j, w in weights[i]:
            p = add(p, scale(mat_point(skins[j], rest[i]), w))
        out.append(p)
    return out


# ---------------------------------------------------------------------------------------------
# Output.


def write_obj(path, positions, triangles):
    """Only v and f lines, in the glb's vertex and triangle order."""
    lines = ["v %.6f %.6f %.6f" % p for p in positions]
    lines += ["f %d %d %d" % (a + 1, b + 1, c + 1) for a, b, c in triangles]
    with open(path, "w", newline="\n") as f:
        f.write("\n".join(lines) + "\n")


class BinaryBuffer:
    def __init__(self):
        self.data = bytearray()
        self.views = []
        self.accessors = []

    def add(self, fmt, values, component, type_, count, target=None, minmax=None):
        while len(self.data) % 4:
            self.data.append(0)
        offset = len(self.data)
        self.data += struct.pack("<" + fmt * len(values), *values)
        view = {"buffer": 0, "byteOffset": offset, "byteLength": len(self.data) - offset}
        if target is not None:
            view["target"] = target
        self.views.append(view)
        accessor = {"bufferView": len(self.views) - 1, "componentType": component, "count": count,
                    "type": type_}
        if minmax is not None:
            accessor["min"], accessor["max"] = minmax
        self.accessors.append(accessor)
        return len(self.accessors) - 1


def vec_minmax(rows):
    return ([min(r[i] for r in rows) for i in range(len(rows[0]))],
            [max(r[i] for r in rows) for i in range(len(rows[0]))])


def vertex_normals(positions, triangles):
    normals = [(0.0, 0.0, 0.0)] * len(positions)
    for a, b, c in triangles:
        n = cross(sub(positions[b], positions[a]), sub(positions[c], positions[a]))
        for i in (a, b, c):
            normals[i] = add(normals[i], n)
    return [tuple(f32(c) for c in normalize(n)) for n in normals]


def main():
    out_dir = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
    os.makedirs(os.path.join(out_dir, "keys"), exist_ok=True)

    mb = build_mesh()
    rest = [tuple(f32(c) for c in p) for p in mb.positions]
    triangles = mb.triangles
    # Skin weights: at most two joints per vertex, float32, summing to 1.
    weights = []
    for w in mb.weights:
        if len(w) == 1:
            weights.append([(w[0][0], 1.0)])
        else:
            w0 = f32(w[0][1])
            weights.append([(w[0][0], w0), (w[1][0], f32(1.0 - w0))])
    normals = vertex_normals(rest, triangles)
    ibms = [[[1.0, 0.0, 0.0, f32(-pos[0])], [0.0, 1.0, 0.0, f32(-pos[1])],
             [0.0, 0.0, 1.0, f32(-pos[2])], [0.0, 0.0, 0.0, 1.0]] for _, _, pos in kJoints]

    # Sample the cycle: frame i at time i / 24 s, i = 0..40, the last a copy of the first.
    foot_vertices = [i for i, w in enumerate(weights)
                     if any(kJoints[j][0].startswith(("foot_", "shin_")) for j, _ in w)]
    hips_rest = kJoints[0][2]

    def pose(frame, **exaggeration):
        p = 2.0 * math.pi * frame / kFrames
        rotations = local_rotations(walk_angles(p, **exaggeration))
        return rotations

    def root_translation(frame):
        # Plant the lowest foot point on y = 0 (the base walk's, also used by its keys).
        rotations = pose(frame)
        feet = skin_positions(rest, weights, ibms, rotations, hips_rest, foot_vertices)
        lowest = min(p[1] for p in feet)
        return tuple(f32(c) for c in (hips_rest[0], hips_rest[1] - lowest, hips_rest[2]))

    frame_rotations = [pose(i) for i in range(kFrames)]
    frame_roots = [root_translation(i) for i in range(kFrames)]
    frame_rotations.append(frame_rotations[0])
    frame_roots.append(frame_roots[0])

    # ---- glTF
    buf = BinaryBuffer()
    pos_acc = buf.add("f", [c for p in rest for c in p], 5126, "VEC3", len(rest), 34962,
                      vec_minmax(rest))
    nrm_acc = buf.add("f", [c for n in normals for c in n], 5126, "VEC3", len(rest), 34962)
    joints_flat, weights_flat = [], []
    for w in weights:
        js = [j for j, _ in w] + [0] * (4 - len(w))
        ws = [x for _, x in w] + [0.0] * (4 - len(w))
        joints_flat += js
        weights_flat += ws
    jnt_acc = buf.add("B", joints_flat, 5121, "VEC4", len(rest), 34962)
    wgt_acc = buf.add("f", weights_flat, 5126, "VEC4", len(rest), 34962)
    idx_acc = buf.add("H", [i for t in triangles for i in t], 5123, "SCALAR", 3 * len(triangles),
                      34963, ([0], [len(rest) - 1]))
    ibm_acc = buf.add("f", [m[r][c] for m in ibms for c in range(4) for r in range(4)], 5126, "MAT4",
                      len(ibms))
    times = [f32(i / kFps) for i in range(kFrames + 1)]
    time_acc = buf.add("f", times, 5126, "SCALAR", len(times), None, ([times[0]], [times[-1]]))

    node_base = 1  # node 0 is the mesh; joint j is node 1 + j
    channels, samplers = [], []
    root_acc = buf.add("f", [c for t in frame_roots for c in t], 5126, "VEC3", len(frame_roots))
    samplers.append({"input": time_acc, "output": root_acc, "interpolation": "LINEAR"})
    channels.append({"sampler": 0, "target": {"node": node_base, "path": "translation"}})
    animated = ["hips", "spine", "head", "upperarm_L", "forearm_L", "upperarm_R", "forearm_R",
                "thigh_L", "shin_L", "foot_L", "thigh_R", "shin_R", "foot_R"]
    for name in animated:
        j = kJointIndex[name]
        acc = buf.add("f", [c for r in frame_rotations for c in r[j]], 5126, "VEC4",
                      len(frame_rotations))
        samplers.append({"input": time_acc, "output": acc, "interpolation": "LINEAR"})
        channels.append({"sampler": len(samplers) - 1, "target": {"node": node_base + j,
                                                                  "path": "rotation"}})

    nodes = [{"name": "Walker", "mesh": 0, "skin": 0}]
    for j, (name, parent, _) in enumerate(kJoints):
        node = {"name": name, "translation": [f32(c) for c in joint_rest_local(j)]}
        children = [node_base + k for k, (_, par, _) in enumerate(kJoints) if par == j]
        if children:
            node["children"] = children
        nodes.append(node)

    gltf = {
        "asset": {"version": "2.0", "generator": "vdg examples/walk/make_walker.py"},
        "scene": 0,
        "scenes": [{"name": "Walk", "nodes": [0, node_base]}],
        "nodes": nodes,
        "meshes": [{"name": "Body", "primitives": [{
            "attributes": {"POSITION": pos_acc, "NORMAL": nrm_acc, "JOINTS_0": jnt_acc,
                           "WEIGHTS_0": wgt_acc},
            "indices": idx_acc, "material": 0, "mode": 4}]}],
        "materials": [{"name": "Skin", "pbrMetallicRoughness": {
            "baseColorFactor": [0.8, 0.62, 0.5, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.8}}],
        "skins": [{"name": "Skeleton", "inverseBindMatrices": ibm_acc, "skeleton": node_base,
                   "joints": [node_base + j for j in range(len(kJoints))]}],
        "animations": [{"name": "Walk", "channels": channels, "samplers": samplers}],
        "buffers": [{"byteLength": 0}],
        "bufferViews": buf.views,
        "accessors": buf.accessors,
    }
    while len(buf.data) % 4:
        buf.data.append(0)
    gltf["buffers"][0]["byteLength"] = len(buf.data)
    text = json.dumps(gltf, separators=(",", ":")).encode("utf-8")
    text += b" " * ((4 - len(text) % 4) % 4)
    glb = struct.pack("<III", 0x46546C67, 2, 12 + 8 + len(text) + 8 + len(buf.data))
    glb += struct.pack("<II", len(text), 0x4E4F534A) + text
    glb += struct.pack("<II", len(buf.data), 0x004E4942) + bytes(buf.data)
    with open(os.path.join(out_dir, "walker.glb"), "wb") as f:
        f.write(glb)

    # ---- Base frames and key deformations (OBJ, the glb's vertex order and triangles).
    for frame in kKeyFrames:
        base = skin_positions(rest, weights, ibms, frame_rotations[frame], frame_roots[frame])
        write_obj(os.path.join(out_dir, "base_f%02d.obj" % frame), base, triangles)
        keys = {
            "side": dict(swing=kSideSwing, bend=kSideBend),
            "front": dict(swing=kFrontSwing, arm_spread=math.radians(kFrontSpreadArmDeg),
                          leg_spread=math.radians(kFrontSpreadLegDeg)),
        }
        for view, exaggeration in keys.items():
            key = skin_positions(rest, weights, ibms, pose(frame, **exaggeration), frame_roots[frame])
            write_obj(os.path.join(out_dir, "keys", "%s_f%02d.obj" % (view, frame)), key, triangles)

    # ---- Manifests (version 2).
    for name, offsets in (("walker.vdg.json", "skinned"), ("walker-world.vdg.json", "world")):
        keys = []
        for frame in kKeyFrames:
            for view, direction in (("front", [0.0, 0.0, 1.0]), ("side", [1.0, 0.0, 0.0])):
                keys.append({"name": "%s_f%02d" % (view, frame), "mesh": "keys/%s_f%02d.obj" % (view, frame),
                             "view": direction, "frame": frame})
        manifest = {
            "version": 2,
            "comment": "Rademacher 99, section 4.3: a 40-frame walk cycle with four key deformations "
                       "(front and side at frames 10 and 30) exaggerating the arm and leg swing; "
                       "offsets %s. Generated by examples/walk/make_walker.py." % offsets,
            "base_animation": {"gltf": "walker.glb", "animation": 0, "fps": 24, "loop": True},
            "offsets": offsets,
            "center": [0.0, 0.9, 0.0],
            "keys": keys,
        }
        # One line per field and per key, like the other examples' manifests.
        fields = ['  "%s": %s' % (k, json.dumps(v)) for k, v in manifest.items() if k != "keys"]
        key_lines = ["    " + json.dumps(k) for k in keys]
        text = "{\n" + ",\n".join(fields) + ',\n  "keys": [\n' + ",\n".join(key_lines) + "\n  ]\n}\n"
        with open(os.path.join(out_dir, name), "w", newline="\n") as f:
            f.write(text)

    print("make_walker: %d vertices, %d triangles, %d joints, %d frames -> %s"
          % (len(rest), len(triangles), len(kJoints), kFrames, out_dir))


if __name__ == "__main__":
    main()
