"""Import a vdg model as a mesh object with shape keys; export an object to a manifest or glTF."""
import os
from typing import Any, Dict, List

import bpy
import numpy as np

from . import axes, model, vdgmodule


def _mesh_from_model(name: str, m: Any) -> Any:
    """A Blender mesh of the model's base (frame 0), triangles and per-vertex UVs."""
    mesh = bpy.data.meshes.new(name)
    verts = axes.to_blender(m.base)
    tris = np.asarray(m.triangles, dtype=np.int32)
    mesh.vertices.add(len(verts))
    mesh.vertices.foreach_set("co", verts.ravel())
    mesh.loops.add(len(tris) * 3)
    mesh.loops.foreach_set("vertex_index", tris.ravel())
    mesh.polygons.add(len(tris))
    mesh.polygons.foreach_set("loop_start", np.arange(0, len(tris) * 3, 3, dtype=np.int32))
    mesh.polygons.foreach_set("loop_total", np.full(len(tris), 3, dtype=np.int32))
    if m.uvs is not None:
        layer = mesh.uv_layers.new(name="UVMap")
        layer.data.foreach_set("uv", np.asarray(m.uvs, dtype=np.float32)[tris.ravel()].ravel())
    mesh.update(calc_edges=True)
    mesh.polygons.foreach_set("use_smooth", np.ones(len(tris), dtype=bool))
    return mesh


def _key_positions(m: Any, key: Any) -> np.ndarray:
    """A key's shape on the frame-0 base (vdg axes): the key mesh, or for an animated model with world
    offsets the offset at the key's frame added to frame 0 (the user's rig poses it)."""
    if not m.animated:
        return np.asarray(key.positions, dtype=np.float32)
    frames = m.base_frames
    return np.asarray(m.base, dtype=np.float32) + (np.asarray(key.positions, dtype=np.float32) - frames[key.frame])


def import_model(context: Any, path: str) -> Any:
    """Loads `path` (manifest or vdg glTF) through vdg.load and links a new mesh object to the scene."""
    vdg = vdgmodule.get()
    try:
        m = vdg.load(path)
    except (vdg.Error, ValueError, TypeError, OSError) as e:
        raise model.AddonError(str(e)) from e
    name = os.path.basename(path)
    for suffix in (".vdg.json", ".json", ".gltf", ".glb"):
        if name.endswith(suffix):
            name = name[: -len(suffix)]
            break
    obj = bpy.data.objects.new(name, _mesh_from_model(name, m))
    context.collection.objects.link(obj)
    obj.shape_key_add(name="Basis", from_mix=False)
    scene = context.scene
    if m.animated:  # vdg frame f is scene frame f: the scene takes the model's range
        scene.frame_start, scene.frame_end = 0, int(m.frame_count) - 1
    s = obj.vdg
    s.sharpness, s.uncovered, s.base_falloff_deg = float(m.sharpness), m.uncovered, float(m.base_falloff_deg)
    s.use_center, s.center = True, tuple(float(c) for c in m.center)
    s.loop, s.comment = bool(m.loop), m.comment
    s.frame_count = int(m.frame_count) if m.animated else 0
    for key in m.keys:
        block = obj.shape_key_add(name=key.name, from_mix=False)
        block.data.foreach_set("co", axes.to_blender(_key_positions(m, key)).ravel())
        item = s.keys.add()
        item.name = block.name
        item.view = tuple(float(c) for c in key.view)
        item.frame = int(key.frame) + (scene.frame_start if m.animated else 0)
        if key.camera is not None:
            item.has_camera = True
            item.camera.eye = tuple(float(c) for c in key.camera.eye)
            item.camera.target = tuple(float(c) for c in key.camera.target)
            item.camera.up = tuple(float(c) for c in key.camera.up)
            item.camera.fov_deg = float(key.camera.fov_deg)
    context.view_layer.objects.active = obj
    obj.select_set(True)
    return obj


def _evaluated_positions(obj: Any, depsgraph: Any) -> np.ndarray:
    """The evaluated (modifier-applied) mesh's positions, object space, Blender axes."""
    evaluated = obj.evaluated_get(depsgraph)
    mesh = evaluated.to_mesh()
    try:
        out = np.empty(len(mesh.vertices) * 3, dtype=np.float32)
        mesh.vertices.foreach_get("co", out)
    finally:
        evaluated.to_mesh_clear()
    if len(out) != len(obj.data.vertices) * 3:
        raise model.AddonError(f"object '{obj.name}': a modifier changes the vertex count; only deforming "
                               "modifiers (Armature) can be exported")
    return out.reshape(-1, 3)


def _build_animated(context: Any, obj: Any) -> Any:
    """Section 4 from an armature-animated object: the base (shape keys at 0) at every scene frame, and
    each key mesh the posed mesh at its frame with that shape key alone at 1 (world offsets)."""
    from . import preview

    scene = context.scene
    first, count = model.frame_range(scene, obj)
    blocks = obj.data.shape_keys.key_blocks
    saved_values = {b.name: b.value for b in blocks}
    saved_frame = scene.frame_current
    frames: List[np.ndarray] = []
    positions: Dict[str, np.ndarray] = {}
    with preview.suspended():
        try:
            for b in blocks:
                b.value = 0.0
            for f in range(count):
                scene.frame_set(first + f)
                frames.append(axes.to_vdg(_evaluated_positions(obj, context.evaluated_depsgraph_get())))
            for k in obj.vdg.keys:
                if not 0 <= k.frame - first < count:
                    raise model.AddonError(f"object '{obj.name}': key '{k.name}' is at frame {k.frame}, "
                                           f"outside the scene's frames {first}..{first + count - 1}")
                block = model.key_block(obj, k.name)
                block.value = 1.0
                scene.frame_set(k.frame)
                positions[k.name] = axes.to_vdg(_evaluated_positions(obj, context.evaluated_depsgraph_get()))
                block.value = 0.0
        finally:
            for name, value in saved_values.items():
                blocks[name].value = value
            scene.frame_set(saved_frame)
    stack = np.ascontiguousarray(np.stack(frames))
    return model.build_call(obj, stack[0], model.key_dicts(obj, positions, first), frames=stack,
                            loop=bool(obj.vdg.loop), fps=float(scene.render.fps / scene.render.fps_base),
                            uvs=model.vertex_uvs(obj.data))


def export_model(context: Any, obj: Any, path: str) -> Any:
    """Builds the object's model and writes a manifest (*.json, with OBJ meshes) or glTF (.gltf/.glb)."""
    if not obj.vdg.keys:
        raise model.AddonError(f"object '{obj.name}' has no vdg keys to export")
    lower = path.lower()
    if not lower.endswith((".json", ".gltf", ".glb")):
        raise model.AddonError(f"{path}: the file name must end in .vdg.json, .gltf or .glb")
    if model.armature_animated(obj):
        m = _build_animated(context, obj)
    elif any(k.frame != 0 for k in obj.vdg.keys):
        raise model.AddonError(f"object '{obj.name}': its keys have frames but no Armature modifier poses the "
                               "mesh; add the rig (docs/blender.md, animated characters) or set the frames to 0")
    else:
        m = model.build_static(obj, with_uvs=True)
    vdg = vdgmodule.get()
    try:
        if lower.endswith(".json"):
            m.save_manifest(path)
        else:
            m.export_gltf(path)
    except (vdg.Error, ValueError, TypeError, OSError) as e:
        raise model.AddonError(str(e)) from e
    return m
