"""Import a vdg model as a mesh object with shape keys; export an object to a manifest or glTF."""
import os
import tempfile
from typing import Any, Dict, List, Optional, Tuple

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
    corner_uvs = getattr(m, "corner_uvs", None)
    if corner_uvs is not None:  # per triangle corner: the loops are the triangles' corners in order
        layer = mesh.uv_layers.new(name="UVMap")
        layer.data.foreach_set("uv", np.asarray(corner_uvs, dtype=np.float32).ravel())
    elif m.uvs is not None:
        layer = mesh.uv_layers.new(name="UVMap")
        layer.data.foreach_set("uv", np.asarray(m.uvs, dtype=np.float32)[tris.ravel()].ravel())
    mesh.update(calc_edges=True)
    mesh.polygons.foreach_set("use_smooth", np.ones(len(tris), dtype=bool))
    _import_materials(mesh, m)
    return mesh


def _srgb_to_linear(c: float) -> float:
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


def _linear_to_srgb(c: float) -> float:
    c = min(max(c, 0.0), 1.0)
    return c * 12.92 if c <= 0.0031308 else 1.055 * c ** (1.0 / 2.4) - 0.055


def _import_image(texture: bytes, path: str) -> Any:
    """A Blender image packed from the texture file's bytes (nothing is left on disk)."""
    name = os.path.basename(path) or "texture.png"
    with tempfile.TemporaryDirectory() as folder:
        file = os.path.join(folder, name)
        with open(file, "wb") as f:
            f.write(texture)
        image = bpy.data.images.load(file)
        image.pack()
    image.filepath = "//" + name
    return image


def _import_materials(mesh: Any, m: Any) -> None:
    """The model's materials as Principled BSDF materials (base colour, image texture) on the mesh."""
    materials = getattr(m, "materials", None) or []
    for spec in materials:
        mat = bpy.data.materials.new(spec.get("name") or "vdg")
        mat.use_nodes = True
        bsdf = next(n for n in mat.node_tree.nodes if n.type == "BSDF_PRINCIPLED")
        colour = [_srgb_to_linear(float(c)) for c in spec.get("base_color", (1.0, 1.0, 1.0))[:3]]
        bsdf.inputs["Base Color"].default_value = (*colour, 1.0)
        mat.diffuse_color = (*colour, 1.0)
        if spec.get("texture"):
            node = mat.node_tree.nodes.new("ShaderNodeTexImage")
            node.image = _import_image(bytes(spec["texture"]), spec.get("texture_path") or "")
            node.location = (bsdf.location.x - 300, bsdf.location.y)
            mat.node_tree.links.new(node.outputs["Color"], bsdf.inputs["Base Color"])
        mesh.materials.append(mat)
    faces = getattr(m, "face_materials", None)
    if materials and faces is not None:
        mesh.polygons.foreach_set("material_index", np.maximum(np.asarray(faces, dtype=np.int32), 0))


def _texture_of(mat: Any) -> Tuple[Optional[bytes], str]:
    """The PNG or JPEG bytes and file name of the image feeding the Principled BSDF's Base Color."""
    if not mat.use_nodes:
        return None, ""
    bsdf = next((n for n in mat.node_tree.nodes if n.type == "BSDF_PRINCIPLED"), None)
    links = bsdf.inputs["Base Color"].links if bsdf is not None else []
    node = links[0].from_node if links else None
    if node is None or node.type != "TEX_IMAGE" or node.image is None:
        return None, ""
    image = node.image
    data: Optional[bytes] = None
    if image.packed_file is not None:
        data = bytes(image.packed_file.data)
    else:
        path = bpy.path.abspath(image.filepath)
        if os.path.isfile(path):
            with open(path, "rb") as f:
                data = f.read()
    if data is None or not (data.startswith(b"\x89PNG") or data.startswith(b"\xff\xd8")):
        return None, ""
    return data, os.path.basename(image.filepath) or image.name


def material_arguments(obj: Any) -> Dict[str, Any]:
    """vdg.build's materials and face_materials from the mesh's material slots (empty without any)."""
    mesh = obj.data
    if not mesh.materials or all(mat is None for mat in mesh.materials):
        return {}
    specs = []
    for i, mat in enumerate(mesh.materials):
        if mat is None:
            specs.append({"name": f"material{i}", "base_color": (1.0, 1.0, 1.0)})
            continue
        colour = mat.diffuse_color
        if mat.use_nodes:
            bsdf = next((n for n in mat.node_tree.nodes if n.type == "BSDF_PRINCIPLED"), None)
            if bsdf is not None:
                colour = bsdf.inputs["Base Color"].default_value
        spec: Dict[str, Any] = {"name": mat.name, "base_color": tuple(_linear_to_srgb(float(c)) for c in colour[:3])}
        data, name = _texture_of(mat)
        if data is not None:
            spec["texture"], spec["texture_path"] = data, name
        specs.append(spec)
    mesh.calc_loop_triangles()
    polys = np.empty(len(mesh.loop_triangles), dtype=np.int32)
    mesh.loop_triangles.foreach_get("polygon_index", polys)
    index = np.empty(len(mesh.polygons), dtype=np.int32)
    mesh.polygons.foreach_get("material_index", index)
    return {"materials": specs, "face_materials": np.ascontiguousarray(index[polys])}


def uv_arguments(obj: Any) -> Dict[str, Any]:
    """vdg.build's uvs (one per vertex) when the UV map allows, else corner_uvs (T, 3, 2); {} without a map."""
    mesh = obj.data
    uvs = model.vertex_uvs(mesh)
    if uvs is not None:
        return {"uvs": uvs}
    layer = mesh.uv_layers.active
    if layer is None:
        return {}
    loop_uv = np.empty(len(mesh.loops) * 2, dtype=np.float32)
    layer.data.foreach_get("uv", loop_uv)
    mesh.calc_loop_triangles()
    loops = np.empty(len(mesh.loop_triangles) * 3, dtype=np.int32)
    mesh.loop_triangles.foreach_get("loops", loops)
    return {"corner_uvs": np.ascontiguousarray(loop_uv.reshape(-1, 2)[loops].reshape(-1, 3, 2))}


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
    if getattr(m, "parts", []):
        raise model.AddonError(
            f"{path}: model parts ('parts') are not supported by the Blender add-on: its shape keys weigh one key set "
            "for the whole mesh (vdg weights, eval and the Python module evaluate parts)")
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
    s.scheme = m.scheme  # and the rbf scheme's kernel and width (docs/weights.md)
    if m.scheme == "rbf":
        s.rbf_kernel, s.rbf_width = m.kernel, float(m.width)
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
                            **uv_arguments(obj), **material_arguments(obj))


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
        m = model.build_static(obj, **uv_arguments(obj), **material_arguments(obj))
    vdg = vdgmodule.get()
    try:
        if lower.endswith(".json"):
            m.save_manifest(path)
        else:
            m.export_gltf(path)
    except (vdg.Error, ValueError, TypeError, OSError) as e:
        raise model.AddonError(str(e)) from e
    return m
