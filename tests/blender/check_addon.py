"""The vdg Blender add-on, installed from its zip, against the vdg tool (run by run_addon_check.sh).

blender -b --factory-startup --python check_addon.py -- CASE VDG SOURCE_DIR ADDON_ZIP OUT_DIR

CASE preview:   examples/spot imported (manifest, and its .glb export), the object moved, rotated and
                scaled; the camera at random positions; the live preview's shape-key values equal
                `vdg weights --views --json` (WEIGHT_TOL) and the evaluated mesh `vdg eval` (POSITION_TOL).
CASE roundtrip: a key made from the camera on Spot, a few of its vertices moved, exported as a manifest
                and a .glb: `vdg info` opens both, `vdg weights` at the key's view gives it weight 1 and
                `vdg eval` there the sculpted shape; re-importing keeps names, views, frames and shapes.
CASE armature:  a small armature-animated column keyed at frame 5 and exported: `vdg eval --frame 5` at
                the key's view equals Blender's posed mesh with that key at 1 (ARMATURE_TOL).
CASE walker:    the animated walker (section 4) imported; at random views and frames the preview's values
                equal vdg.Model.weights(view, frame)["keys"] and a value outside [0, 1] widens the slider.
Every check prints a "check:" line; a failure raises (Blender exits 1). "check: done" ends a run.
"""
import json
import os
import random
import subprocess
import sys
import time

import bpy
import numpy as np
from mathutils import Euler, Vector

WEIGHT_TOL = 1e-6    # shape-key values against vdg's float weights
POSITION_TOL = 1e-5  # float32 blended positions of a model about 1 unit across
SHAPE_TOL = 1e-6     # float32 positions through the axis swap (exact) and a file round trip
VIEW_TOL = 1e-6      # unit view directions through files
ARMATURE_TOL = 1e-4  # posed positions through Blender's and vdg's float32 paths
CAMERAS = 20


def arguments():
    argv = sys.argv[sys.argv.index("--") + 1:]
    if len(argv) != 5:
        raise SystemExit("usage: blender -b --python check_addon.py -- CASE VDG SOURCE_DIR ADDON_ZIP OUT_DIR")
    return argv


def install(zip_path):
    """Installs and enables the add-on from the zip (into BLENDER_USER_SCRIPTS), as an artist does."""
    bpy.ops.preferences.addon_install(filepath=zip_path, overwrite=True)
    bpy.ops.preferences.addon_enable(module="vdg_addon")
    import vdg_addon  # noqa: F401  (installed above)
    folder = os.path.dirname(vdg_addon.__file__)
    if not folder.startswith(os.environ.get("BLENDER_USER_SCRIPTS", "/nonexistent")):
        raise AssertionError(f"the add-on was loaded from {folder}, not from the zip's install")
    from vdg_addon import vdgmodule
    vdg = vdgmodule.get()
    if not os.path.dirname(vdg.__file__) == folder:
        raise AssertionError(f"import vdg found {vdg.__file__}, not the zip's copy in {folder}")
    print(f"check: add-on installed from the zip into {folder}, vdg {vdg.__version__} from it")
    for name in [o.name for o in bpy.data.objects if o.type != "CAMERA"]:
        bpy.data.objects.remove(bpy.data.objects[name])
    return vdg


def run(cmd):
    out = subprocess.run(cmd, capture_output=True, text=True)
    if out.returncode != 0:
        raise AssertionError(f"{' '.join(cmd)} failed: {out.stderr.strip()}")
    return out.stdout


def import_model(path):
    before = set(bpy.data.objects)
    if bpy.ops.vdg.import_model(filepath=path) != {"FINISHED"}:
        raise AssertionError(f"vdg.import_model({path}) did not finish")
    new = [o for o in bpy.data.objects if o not in before]
    if len(new) != 1 or new[0].type != "MESH":
        raise AssertionError(f"importing {path} made {new}, not one mesh object")
    return new[0]


def to_vdg(p):
    p = np.asarray(p, dtype=np.float64).reshape(-1, 3)
    return np.stack([p[:, 0], p[:, 2], -p[:, 1]], axis=1)


def eye_of(obj, cam):
    """The camera's position in the object's local space, vdg axes, computed here independently."""
    m = np.array(obj.matrix_world, dtype=np.float64)
    c = np.append(np.array(cam.matrix_world.translation, dtype=np.float64), 1.0)
    return to_vdg(np.linalg.solve(m, c)[:3])[0]


def random_camera(rng, cam, obj, radius):
    """The camera somewhere around the object (any direction, 2-4 radii away)."""
    d = Vector([rng.gauss(0.0, 1.0) for _ in range(3)]).normalized()
    cam.location = obj.matrix_world.translation + d * radius * rng.uniform(2.0, 4.0)
    bpy.context.view_layer.update()  # depsgraph_update_post: the live preview sets the values


def values(obj):
    return {b.name: b.value for b in obj.data.shape_keys.key_blocks[1:]}


def evaluated_vdg(obj):
    deps = bpy.context.evaluated_depsgraph_get()
    ev = obj.evaluated_get(deps)
    mesh = ev.to_mesh()
    co = np.empty(len(mesh.vertices) * 3, dtype=np.float32)
    mesh.vertices.foreach_get("co", co)
    ev.to_mesh_clear()
    return to_vdg(co)


def obj_positions(path):
    with open(path, encoding="utf-8") as f:
        return np.array([[float(x) for x in line.split()[1:4]] for line in f if line.startswith("v ")])


def compare_preview(vdg_tool, model_path, obj, cam, rng, out, count, label, options=()):
    radius = max(obj.dimensions) / 2.0
    eyes, seen = [], []
    for _ in range(count):
        random_camera(rng, cam, obj, radius)
        eyes.append(eye_of(obj, cam).tolist())
        seen.append((values(obj), evaluated_vdg(obj)))
    views_file = os.path.join(out, f"{label}_eyes.json")
    with open(views_file, "w", encoding="utf-8") as f:
        json.dump([{"eye": e} for e in eyes], f)
    expected = json.loads(run([vdg_tool, "weights", model_path, "--views", views_file, "--json", *options]))
    worst_w = worst_p = 0.0
    moved = 0
    for i, (eye, (vals, positions)) in enumerate(zip(eyes, seen)):
        keys = expected[i]["keys"]
        for name, value in vals.items():
            worst_w = max(worst_w, abs(value - keys.get(name, 0.0)))
        moved += sum(1 for v in vals.values() if v > 0.0)
        mesh_file = os.path.join(out, f"{label}_eval.obj")
        run([vdg_tool, "eval", model_path, "--eye=" + ",".join(repr(c) for c in eye), "-o", mesh_file, "-q", *options])
        ref = obj_positions(mesh_file)
        if ref.shape != positions.shape:
            raise AssertionError(f"{label}: vdg eval has {ref.shape[0]} vertices, Blender {positions.shape[0]}")
        worst_p = max(worst_p, float(np.abs(ref - positions).max()))
    if moved == 0:
        raise AssertionError(f"{label}: the preview set no shape-key value above 0")
    if worst_w > WEIGHT_TOL:
        raise AssertionError(f"{label}: a shape-key value differs from vdg weights by {worst_w:.3g}")
    if worst_p > POSITION_TOL:
        raise AssertionError(f"{label}: the evaluated mesh differs from vdg eval by {worst_p:.3g}")
    print(f"check: {label}: {count} cameras, values = vdg weights (worst {worst_w:.2g}), "
          f"evaluated mesh = vdg eval (worst {worst_p:.2g})")


def case_preview(vdg_tool, src, out):
    manifest = os.path.join(src, "examples", "spot", "spot.vdg.json")
    rng = random.Random(26)
    scene = bpy.context.scene
    scene.vdg_live_preview = True
    obj = import_model(manifest)
    # Moved, rotated and scaled: the view is the camera carried into the object's space.
    obj.location = (0.7, -0.3, 0.2)
    obj.rotation_euler = Euler((0.3, -0.2, 1.1))
    obj.scale = (1.3, 1.3, 1.3)
    names = [b.name for b in obj.data.shape_keys.key_blocks]
    with open(manifest, encoding="utf-8") as f:
        expected = ["Basis"] + [k["name"] for k in json.load(f)["keys"]]
    if names != expected:
        raise AssertionError(f"shape keys {names}, expected {expected}")
    start = time.time()
    compare_preview(vdg_tool, manifest, obj, scene.camera, rng, out, CAMERAS, "spot manifest")
    print(f"check: (20 cameras in {time.time() - start:.1f} s)")
    # A crowd member: a second copy elsewhere, blending for its own view.
    glb = os.path.join(out, "spot.glb")
    run([vdg_tool, "export", manifest, "-o", glb, "-q"])
    other = import_model(glb)
    other.location = (-2.5, 1.0, 0.0)
    other.rotation_euler = Euler((0.0, 0.0, -0.8))
    compare_preview(vdg_tool, glb, other, scene.camera, rng, out, 5, "spot glb (second object)")
    compare_preview(vdg_tool, manifest, obj, scene.camera, rng, out, 3, "spot manifest (with the crowd)")
    obj.vdg.sharpness = 2.5  # a setting change rebuilds the object's model and refreshes the values
    compare_preview(vdg_tool, manifest, obj, scene.camera, rng, out, 3, "spot manifest (sharpness 2.5)",
                    ("--sharpness", "2.5"))


def case_roundtrip(vdg_tool, src, out):
    vdg_mod = sys.modules["vdg"]
    manifest = os.path.join(src, "examples", "spot", "spot.vdg.json")
    scene = bpy.context.scene
    scene.vdg_live_preview = True
    obj = import_model(manifest)
    original = vdg_mod.load(manifest)
    images = [n.image for mat in obj.data.materials for n in mat.node_tree.nodes if n.type == "TEX_IMAGE"]
    if len(images) != 1 or tuple(images[0].size) != (1024, 1024):
        raise AssertionError(f"Spot imported with images {[tuple(i.size) for i in images]}, not its 1024x1024 texture")
    print(f"check: Spot imported with its material '{obj.data.materials[0].name}' and its 1024x1024 texture")
    bpy.context.view_layer.objects.active = obj
    cam = scene.camera
    cam.location = (1.8, -2.2, 1.4)
    bpy.context.view_layer.update()
    if bpy.ops.vdg.key_from_camera(name="mine") != {"FINISHED"}:
        raise AssertionError("vdg.key_from_camera did not finish")
    key = obj.vdg.keys[-1]
    expected_view = eye_of(obj, cam) - np.array(obj.vdg.center)
    expected_view /= np.linalg.norm(expected_view)
    if key.name != "mine" or not key.has_camera or np.abs(np.array(key.view) - expected_view).max() > VIEW_TOL:
        raise AssertionError(f"key {key.name} view {tuple(key.view)}, expected 'mine' at {expected_view}")
    block = obj.data.shape_keys.key_blocks["mine"]
    for i in range(0, 200, 10):  # the artist's sculpt: a few vertices pulled out
        block.data[i].co += Vector((0.0, 0.0, 0.08))
    bpy.context.view_layer.update()
    if abs(block.value - 1.0) > WEIGHT_TOL:
        raise AssertionError(f"at the key's own camera the preview gives 'mine' {block.value}, not 1")
    print(f"check: key 'mine' from the camera at view {tuple(round(c, 4) for c in key.view)}; preview gives it 1")
    sculpt = to_vdg([b.co for b in block.data])
    # Look through: the key camera comes back; a direction key puts the camera on its view.
    key_camera = cam.matrix_world.copy()
    cam.location = (-3.0, 1.0, 0.5)
    bpy.context.view_layer.update()
    for index in (len(obj.vdg.keys) - 1, 0):
        bpy.context.view_layer.objects.active = obj
        if bpy.ops.vdg.look_through(index=index) != {"FINISHED"}:
            raise AssertionError(f"vdg.look_through({index}) did not finish")
        k = obj.vdg.keys[index]
        seen = eye_of(obj, cam) - np.array(obj.vdg.center)
        seen /= np.linalg.norm(seen)
        value = obj.data.shape_keys.key_blocks[k.name].value
        if np.abs(seen - np.array(k.view)).max() > VIEW_TOL or abs(value - 1.0) > WEIGHT_TOL:
            raise AssertionError(f"looking through '{k.name}' sees {seen} (key {tuple(k.view)}), value {value}")
        if k.has_camera and (cam.matrix_world.translation - key_camera.translation).length > 1e-5:
            raise AssertionError(f"looking through '{k.name}' puts the camera at {cam.matrix_world.translation}")
    print("check: look through 'mine' (its key camera) and 'front' (its direction): the view is the key's, its value 1")
    for name in ("mine.vdg.json", "mine.glb"):
        path = os.path.join(out, name)
        bpy.context.view_layer.objects.active = obj
        if bpy.ops.vdg.export_model(filepath=path) != {"FINISHED"}:
            raise AssertionError(f"vdg.export_model({path}) did not finish")
        info = run([vdg_tool, "info", path])
        if "texture" not in info:
            raise AssertionError(f"{name}: vdg info shows no texture:\n{info}")
        exported = vdg_mod.load(path)
        if original.corner_uvs is not None:
            uv_error = float(np.abs(np.asarray(exported.corner_uvs) - np.asarray(original.corner_uvs)).max())
            if uv_error > SHAPE_TOL:
                raise AssertionError(f"{name}: the corner uvs moved by {uv_error:.3g}")
        view = ",".join(repr(float(c)) for c in key.view)
        w = json.loads(run([vdg_tool, "weights", path, "--view=" + view, "--json"]))["keys"]
        if abs(w.get("mine", 0.0) - 1.0) > WEIGHT_TOL:
            raise AssertionError(f"{name}: vdg weights at the key's view gives 'mine' {w.get('mine')}")
        run([vdg_tool, "eval", path, "--view=" + view, "-o", os.path.join(out, "mine_eval.obj"), "-q"])
        worst = float(np.abs(obj_positions(os.path.join(out, "mine_eval.obj")) - sculpt).max())
        if worst > POSITION_TOL:
            raise AssertionError(f"{name}: vdg eval at the key's view is {worst:.3g} from the sculpted key")
        again = import_model(path)
        for a, b in zip(obj.vdg.keys, again.vdg.keys):
            if a.name != b.name or a.frame != b.frame or np.abs(np.array(a.view) - np.array(b.view)).max() > VIEW_TOL:
                raise AssertionError(f"{name}: key {a.name} {tuple(a.view)} f{a.frame} came back as "
                                     f"{b.name} {tuple(b.view)} f{b.frame}")
        if len(obj.vdg.keys) != len(again.vdg.keys):
            raise AssertionError(f"{name}: {len(obj.vdg.keys)} keys went out, {len(again.vdg.keys)} came back")
        back = again.vdg.keys["mine"]
        if not back.has_camera or np.abs(np.array(back.camera.eye) - np.array(key.camera.eye)).max() > 1e-5:
            raise AssertionError(f"{name}: key 'mine' lost its camera")
        shape = to_vdg([b.co for b in again.data.shape_keys.key_blocks["mine"].data])
        if shape.shape == sculpt.shape and float(np.abs(shape - sculpt).max()) > SHAPE_TOL:
            raise AssertionError(f"{name}: the re-imported key 'mine' moved")
        model = vdg_mod.load(path)
        print(f"check: {name}: vdg info opens it (texture, corner uvs kept), 'mine' weighs 1 at its view, vdg eval there = the sculpt "
              f"(worst {worst:.2g}); re-import keeps {len(model.keys)} names, views, frames and the camera")
        bpy.data.objects.remove(again)
    # Errors reach the user as one report line, never a traceback.
    bpy.context.view_layer.objects.active = obj
    try:
        bpy.ops.vdg.export_model(filepath=os.path.join(out, "bad.txt"))
        raise AssertionError("exporting to bad.txt did not fail")
    except RuntimeError as e:
        if "Traceback" in str(e) or ".vdg.json" not in str(e):
            raise AssertionError(f"the export error is not one clear line: {e}") from None
        print(f"check: a wrong file name is one report line: {str(e).strip()}")
    # A model with per-part key sets (docs/weights.md) is refused on import, in one report line.
    cubist = os.path.join(src, "examples", "spot", "spot-cubist.vdg.json")
    try:
        bpy.ops.vdg.import_model(filepath=cubist)
        raise AssertionError("importing a model with parts did not fail")
    except RuntimeError as e:
        if "Traceback" in str(e) or "model parts ('parts') are not supported by the Blender add-on" not in str(e):
            raise AssertionError(f"the parts refusal is not one clear line: {e}") from None
        print(f"check: a model with parts is one report line: {str(e).strip()}")
    # A model of the rbf weight scheme (docs/weights.md): the object keeps the scheme, its kernel and
    # width; the preview weighs every key as vdg weights does; the export (glTF extras v4) loads as the
    # same model; a kernel changed on the object is the exported model's.
    rbf = os.path.join(src, "examples", "spot", "spot-rbf.vdg.json")
    rbf_obj = import_model(rbf)
    s = rbf_obj.vdg
    if (s.scheme, s.rbf_kernel, round(s.rbf_width, 6)) != ("rbf", "gaussian", 60.0):
        raise AssertionError(f"the rbf model imported as {s.scheme}, {s.rbf_kernel}, {s.rbf_width}")
    compare_preview(vdg_tool, rbf, rbf_obj, scene.camera, random.Random(31), out, 5, "spot rbf manifest")
    s.rbf_kernel, s.rbf_width = "wendland", 75.0
    bpy.context.view_layer.objects.active = rbf_obj
    rbf_glb = os.path.join(out, "spot-rbf-wendland.glb")
    if bpy.ops.vdg.export_model(filepath=rbf_glb) != {"FINISHED"}:
        raise AssertionError(f"vdg.export_model({rbf_glb}) did not finish")
    exported = vdg_mod.load(rbf_glb)
    if (exported.scheme, exported.kernel, exported.width) != ("rbf", "wendland", 75.0):
        raise AssertionError(f"the rbf export is {exported.scheme}, {exported.kernel}, {exported.width}")
    compare_preview(vdg_tool, rbf_glb, rbf_obj, scene.camera, random.Random(32), out, 5, "spot rbf wendland glb")
    print("check: an rbf model keeps its scheme, kernel and width through import, preview and export")
    bpy.ops.preferences.addon_disable(module="vdg_addon")
    left = [n for n in ("vdg", "vdg_live_preview") if hasattr(bpy.types.Object, n) or hasattr(bpy.types.Scene, n)]
    handlers = [h.__name__ for h in bpy.app.handlers.depsgraph_update_post + bpy.app.handlers.frame_change_post
                if h.__module__.startswith("vdg_addon")]
    left += [c for c in ("VDG_OT_key_from_camera", "VDG_PT_panel", "VdgObjectSettings") if hasattr(bpy.types, c)]
    if left or handlers:
        raise AssertionError(f"disabling the add-on left {left} {handlers}")
    bpy.ops.preferences.addon_enable(module="vdg_addon")
    if not hasattr(bpy.types.Object, "vdg") or len(obj.vdg.keys) != 6:
        raise AssertionError("re-enabling the add-on did not bring the keys back")
    print("check: disable removes the properties and handlers; enable again finds the keys stored on the object")


def case_walker(vdg_tool, src, out):
    vdg_mod = sys.modules["vdg"]
    manifest = os.path.join(src, "examples", "walk", "walker-world.vdg.json")
    model = vdg_mod.load(manifest)
    scene = bpy.context.scene
    scene.vdg_live_preview = True
    obj = import_model(manifest)
    frames = [k.frame for k in obj.vdg.keys]
    if frames != [k.frame for k in model.keys] or (scene.frame_start, scene.frame_end) != (0, model.frame_count - 1):
        raise AssertionError(f"key frames {frames}, scene {scene.frame_start}..{scene.frame_end}")
    rng = random.Random(4)
    cam = scene.camera
    worst, outside, positive = 0.0, 0, 0
    for i in range(CAMERAS):
        frame = rng.randrange(model.frame_count)
        scene.frame_set(frame)
        random_camera(rng, cam, obj, max(obj.dimensions) / 2.0)
        expected = model.weights(model.view_from_eye(eye_of(obj, cam)), frame=float(frame))["keys"]
        for name, value in values(obj).items():
            worst = max(worst, abs(value - expected[name]))
            positive += value > 0.0
            block = obj.data.shape_keys.key_blocks[name]
            if not block.slider_min <= expected[name] <= block.slider_max:
                raise AssertionError(f"key {name} weight {expected[name]} outside its slider")
            outside += not 0.0 <= expected[name] <= 1.0
    if positive == 0:
        raise AssertionError("walker: the preview set no shape-key value above 0")
    from vdg_addon import preview
    block = obj.data.shape_keys.key_blocks["front_f10"]
    preview.apply_weights(obj, {"front_f10": 1.3, "side_f10": -0.4})
    side = obj.data.shape_keys.key_blocks["side_f10"]
    if abs(block.value - 1.3) > WEIGHT_TOL or abs(side.value + 0.4) > WEIGHT_TOL:
        raise AssertionError(f"values 1.3 and -0.4 were written as {block.value} and {side.value}")
    print(f"check: time-coefficient values outside [0, 1] widen the sliders: front_f10 = {block.value:.2f} "
          f"(max {block.slider_max}), side_f10 = {side.value:.2f} (min {side.slider_min})")
    if worst > WEIGHT_TOL:
        raise AssertionError(f"walker: a shape-key value differs from vdg.Model.weights by {worst:.3g}")
    print(f"check: walker imported with key frames {frames}; {CAMERAS} views and frames: values = "
          f"vdg.Model.weights(view, frame) (worst {worst:.2g}); {outside} outside [0, 1] within the sliders")


def rigged_column():
    """A 2-bone armature bending a subdivided column over frames 0..10 (a small animated character)."""
    bpy.ops.mesh.primitive_cylinder_add(vertices=8, radius=0.2, depth=2.0, location=(0.0, 0.0, 1.0))
    column = bpy.context.active_object
    bpy.ops.object.mode_set(mode="EDIT")
    bpy.ops.mesh.subdivide(number_cuts=6)
    bpy.ops.object.mode_set(mode="OBJECT")
    arm_data = bpy.data.armatures.new("rig")
    rig = bpy.data.objects.new("rig", arm_data)
    bpy.context.collection.objects.link(rig)
    bpy.context.view_layer.objects.active = rig
    bpy.ops.object.mode_set(mode="EDIT")
    lower = arm_data.edit_bones.new("lower")
    lower.head, lower.tail = (0.0, 0.0, 0.0), (0.0, 0.0, 1.0)
    upper = arm_data.edit_bones.new("upper")
    upper.head, upper.tail, upper.parent = (0.0, 0.0, 1.0), (0.0, 0.0, 2.0), lower
    bpy.ops.object.mode_set(mode="OBJECT")
    for name in ("lower", "upper"):
        group = column.vertex_groups.new(name=name)
        for v in column.data.vertices:
            w = min(1.0, max(0.0, v.co.z - 0.5)) if name == "upper" else 1.0 - min(1.0, max(0.0, v.co.z - 0.5))
            if w > 0.0:
                group.add([v.index], w, "REPLACE")
    modifier = column.modifiers.new("Armature", "ARMATURE")
    modifier.object = rig
    bone = rig.pose.bones["upper"]
    bone.rotation_mode = "XYZ"
    for frame, angle in ((0, 0.0), (5, 0.6), (10, 0.0)):
        bone.rotation_euler = (angle, 0.0, 0.0)
        bone.keyframe_insert("rotation_euler", frame=frame)
    scene = bpy.context.scene
    scene.frame_start, scene.frame_end = 0, 10
    bpy.context.view_layer.objects.active = column
    return column


def case_armature(vdg_tool, src, out):
    """Keys at frame 5 of an armature-animated mesh, exported (section 4, world offsets): vdg eval at the key's
    view and frame equals Blender's posed mesh with that shape key alone at 1."""
    scene = bpy.context.scene
    column = rigged_column()
    scene.frame_set(5)
    for name, view in (("front", (0.0, 0.0, 1.0)), ("side", (1.0, 0.0, 0.0)), ("top", (0.0, 1.0, 0.2))):
        if bpy.ops.vdg.key_from_view(name=name, direction=view) != {"FINISHED"}:
            raise AssertionError(f"vdg.key_from_view({name}) did not finish")
    frames = [k.frame for k in column.vdg.keys]
    if frames != [5, 5, 5]:
        raise AssertionError(f"keys made at frame 5 store frames {frames}")
    block = column.data.shape_keys.key_blocks["front"]
    for v in block.data:
        if v.co.z > 1.5:
            v.co.y -= 0.15  # the upper part pushed towards the front key's eye
    path = os.path.join(out, "column.vdg.json")
    if bpy.ops.vdg.export_model(filepath=path) != {"FINISHED"}:
        raise AssertionError("vdg.export_model did not finish")
    info = run([vdg_tool, "info", path])
    # The live preview on the rigged mesh: values = the exported model's weights at the scene's frame.
    exported = sys.modules["vdg"].load(path)
    scene.vdg_live_preview = True
    rng = random.Random(7)
    worst, positive = 0.0, 0
    for frame in (0, 3, 5, 8):
        scene.frame_set(frame)
        random_camera(rng, scene.camera, column, 1.0)
        expected = exported.weights(exported.view_from_eye(eye_of(column, scene.camera)), frame=float(frame))["keys"]
        worst = max(worst, max(abs(v - expected[n]) for n, v in values(column).items()))
        positive += sum(1 for v in values(column).values() if v > 0.0)
    if positive == 0:
        raise AssertionError("rigged column: the preview set no shape-key value above 0")
    if worst > WEIGHT_TOL:
        raise AssertionError(f"rigged column: a preview value differs from the exported model's weight by {worst:.3g}")
    print(f"check: rigged column: preview values at frames 0, 3, 5, 8 = the exported model's weights (worst {worst:.2g}, {positive} values > 0)")
    scene.vdg_live_preview = False
    for b in column.data.shape_keys.key_blocks[1:]:
        b.value = 0.0
    block.value = 1.0
    column.vdg.preview = False
    scene.frame_set(5)
    posed = evaluated_vdg(column)
    run([vdg_tool, "eval", path, "--view=0,0,1", "--frame", "5", "-o", os.path.join(out, "column_eval.obj"), "-q"])
    worst = float(np.abs(obj_positions(os.path.join(out, "column_eval.obj")) - posed).max())
    if worst > ARMATURE_TOL:
        raise AssertionError(f"vdg eval --frame 5 at 'front' is {worst:.3g} from Blender's posed key mesh")
    moved = float(np.abs(posed - to_vdg([v.co for v in column.data.vertices])).max())
    print(f"check: rigged column keyed at frame 5, exported ({info.count(chr(10))} info lines); vdg eval --frame 5 "
          f"at 'front' = Blender's posed key mesh (worst {worst:.2g}; the pose moves it {moved:.2f})")


def main():
    case, vdg_tool, src, zip_path, out = arguments()
    install(zip_path)
    cases = {"preview": case_preview, "roundtrip": case_roundtrip, "walker": case_walker,
             "armature": case_armature}
    if case not in cases:
        raise SystemExit(f"unknown case {case}")
    cases[case](vdg_tool, src, out)
    print("check: done")


main()
