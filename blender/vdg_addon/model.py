"""Blender object <-> vdg model: the arrays, the key list, building, importing and the cache."""
import hashlib
import math
from typing import Any, Dict, List, Optional, Tuple

import numpy as np
from mathutils import Vector

from . import axes, vdgmodule


class AddonError(Exception):
    """A user-facing error: one line that names the object, key or file."""


def shape_key_positions(key_block: Any) -> np.ndarray:
    """A shape key's absolute positions, Blender axes, (V, 3) float32."""
    out = np.empty(len(key_block.data) * 3, dtype=np.float32)
    key_block.data.foreach_get("co", out)
    return out.reshape(-1, 3)


def base_positions(obj: Any) -> np.ndarray:
    """The Basis (reference key) positions, or the mesh's when it has no shape keys; Blender axes."""
    keys = obj.data.shape_keys
    if keys is not None and keys.reference_key is not None:
        return shape_key_positions(keys.reference_key)
    mesh = obj.data
    out = np.empty(len(mesh.vertices) * 3, dtype=np.float32)
    mesh.vertices.foreach_get("co", out)
    return out.reshape(-1, 3)


def triangles(mesh: Any) -> np.ndarray:
    """The mesh's faces as triangles (Blender's own triangulation), (T, 3) int32."""
    mesh.calc_loop_triangles()
    out = np.empty(len(mesh.loop_triangles) * 3, dtype=np.int32)
    mesh.loop_triangles.foreach_get("vertices", out)
    return out.reshape(-1, 3)


def vertex_uvs(mesh: Any) -> Optional[np.ndarray]:
    """Per-vertex UVs (V, 2) from the active UV map when every vertex has one UV; else None."""
    layer = mesh.uv_layers.active
    if layer is None or len(mesh.loops) == 0:
        return None
    loop_uv = np.empty(len(mesh.loops) * 2, dtype=np.float32)
    layer.data.foreach_get("uv", loop_uv)
    loop_uv = loop_uv.reshape(-1, 2)
    loop_vertex = np.empty(len(mesh.loops), dtype=np.int32)
    mesh.loops.foreach_get("vertex_index", loop_vertex)
    uvs = np.zeros((len(mesh.vertices), 2), dtype=np.float32)
    uvs[loop_vertex] = loop_uv
    if np.abs(uvs[loop_vertex] - loop_uv).max(initial=0.0) > 1e-6:
        return None  # a seam splits UVs but not vertices: vdg keeps one UV per vertex
    return uvs


def center_of(obj: Any) -> np.ndarray:
    """The centre views are measured from (vdg axes): obj.vdg.center, or the Basis's bounding-box centre."""
    settings = obj.vdg
    if settings.use_center:
        return np.array(settings.center, dtype=np.float64)
    base = axes.to_vdg(base_positions(obj)).astype(np.float64)
    if len(base) == 0:
        raise AddonError(f"object '{obj.name}': the mesh has no vertices")
    return 0.5 * (base.min(axis=0) + base.max(axis=0))


def eye_in_vdg(obj: Any, world_point: Any) -> np.ndarray:
    """A world-space point carried into the object's local space, in vdg axes (float64)."""
    local = obj.matrix_world.inverted() @ Vector(world_point)
    return np.array(axes.vec_to_vdg(local), dtype=np.float64)


def view_from_eye(obj: Any, world_eye: Any) -> np.ndarray:
    """normalize(eye - centre) in vdg axes, the eye given in world space (vdg's viewFromEye)."""
    d = eye_in_vdg(obj, world_eye) - center_of(obj)
    n = float(np.linalg.norm(d))
    if not math.isfinite(n) or n < 1e-12:
        raise AddonError(f"object '{obj.name}': the camera is at the model's centre, so it gives no view")
    return d / n


def armature_animated(obj: Any) -> bool:
    """True when an enabled Armature modifier with an armature object deforms the mesh (section 4)."""
    return any(m.type == "ARMATURE" and m.object is not None and m.show_viewport for m in obj.modifiers)


def frame_range(scene: Any, obj: Any) -> Tuple[int, int]:
    """(first scene frame, frame count) of the model's animation: vdg frame f = scene frame first + f."""
    count = obj.vdg.frame_count or (scene.frame_end - scene.frame_start + 1)
    return scene.frame_start, max(1, count)


def settings_kwargs(obj: Any) -> Dict[str, Any]:
    """vdg.build's keyword arguments from obj.vdg."""
    s = obj.vdg
    kwargs = {"sharpness": float(s.sharpness), "uncovered": s.uncovered, "scheme": s.scheme,
              "base_falloff_deg": float(s.base_falloff_deg), "center": center_of(obj), "comment": s.comment}
    if s.scheme == "rbf":
        kwargs.update(kernel=s.rbf_kernel, width=float(s.rbf_width))
    return kwargs


def key_block(obj: Any, name: str) -> Any:
    """The shape key of a vdg key, or an AddonError naming both."""
    keys = obj.data.shape_keys
    block = keys.key_blocks.get(name) if keys is not None else None
    if block is None:
        raise AddonError(f"object '{obj.name}': vdg key '{name}' has no shape key of that name")
    return block


def key_dicts(obj: Any, positions: Dict[str, np.ndarray], first_frame: int = 0) -> List[Any]:
    """vdg.build's key list as vdg.Key objects: name, positions (vdg axes), view, camera when stored, frame."""
    vdg = vdgmodule.get()
    out = []
    for k in obj.vdg.keys:
        camera = None
        if k.has_camera:
            camera = vdg.Camera(np.array(k.camera.eye, dtype=np.float64), np.array(k.camera.target, dtype=np.float64),
                                np.array(k.camera.up, dtype=np.float64), float(k.camera.fov_deg))
        try:
            out.append(vdg.Key(k.name, positions[k.name], view=np.array(k.view, dtype=np.float64), camera=camera,
                               frame=int(k.frame) - first_frame))
        except (vdg.Error, ValueError, TypeError) as e:
            raise AddonError(f"object '{obj.name}': key '{k.name}': {e}") from e
    return out


def build_call(obj: Any, base: np.ndarray, keys: List[Dict[str, Any]], **extra: Any) -> Any:
    """vdg.build(...) with the object's settings; vdg's errors become AddonErrors naming the object."""
    vdg = vdgmodule.get()
    kwargs = settings_kwargs(obj)
    kwargs.update(extra)
    try:
        return vdg.build(base, triangles(obj.data), keys, **kwargs)
    except (vdg.Error, ValueError, TypeError) as e:
        raise AddonError(f"object '{obj.name}': {e}") from e


def build_static(obj: Any, **extra: Any) -> Any:
    """The vdg model of a static object: Basis and shape keys (their positions) in vdg axes; `extra` goes to
    vdg.build (uvs or corner_uvs, materials and face_materials on export)."""
    if not obj.vdg.keys:
        raise AddonError(f"object '{obj.name}' has no vdg keys")
    positions = {k.name: axes.to_vdg(shape_key_positions(key_block(obj, k.name))) for k in obj.vdg.keys}
    keys = key_dicts(obj, positions, first_frame=0)
    return build_call(obj, axes.to_vdg(base_positions(obj)), keys, **extra)


def build_preview(obj: Any, scene: Any) -> Any:
    """The model the preview's weights come from.

    Static: build_static. Animated: the keys' weights depend on the views, the key frames, the frame
    count and looping only (section 4.2), so the base frames are the Basis repeated; export evaluates
    the real ones.
    """
    if not armature_animated(obj) and all(k.frame == 0 for k in obj.vdg.keys) and obj.vdg.frame_count == 0:
        return build_static(obj)
    first, count = frame_range(scene, obj)
    base = axes.to_vdg(base_positions(obj))
    positions = {k.name: axes.to_vdg(shape_key_positions(key_block(obj, k.name))) for k in obj.vdg.keys}
    frames = np.ascontiguousarray(np.broadcast_to(base, (count,) + base.shape))
    return build_call(obj, base, key_dicts(obj, positions, first), frames=frames, loop=bool(obj.vdg.loop),
                      fps=float(obj.vdg.fps))


def signature(obj: Any, scene: Any) -> str:
    """A digest of everything the preview model depends on (positions, keys, settings, frame range)."""
    h = hashlib.sha1()
    h.update(base_positions(obj).tobytes())
    h.update(triangles(obj.data).tobytes())
    s = obj.vdg
    for k in s.keys:
        block = obj.data.shape_keys.key_blocks.get(k.name) if obj.data.shape_keys else None
        h.update(repr((k.name, tuple(k.view), k.frame, k.has_camera)).encode())
        if block is not None:
            h.update(shape_key_positions(block).tobytes())
    h.update(repr((s.sharpness, s.uncovered, s.scheme, s.rbf_kernel, s.rbf_width, s.base_falloff_deg,
                   s.use_center, tuple(s.center), s.loop,
                   s.frame_count, armature_animated(obj), frame_range(scene, obj))).encode())
    return h.hexdigest()


class ModelCache:
    """vdg models per object, rebuilt only when signature() changes."""

    def __init__(self) -> None:
        self._entries: Dict[int, Tuple[str, Any]] = {}

    def get(self, obj: Any, scene: Any) -> Any:
        """The object's preview model, built or reused."""
        key = obj.as_pointer()
        sig = signature(obj, scene)
        entry = self._entries.get(key)
        if entry is not None and entry[0] == sig:
            return entry[1]
        model = build_preview(obj, scene)
        self._entries[key] = (sig, model)
        return model

    def clear(self) -> None:
        """Forgets every model (new file, unregister)."""
        self._entries.clear()


CACHE = ModelCache()
