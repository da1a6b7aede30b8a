"""Operators under bpy.ops.vdg: keys from a camera or a direction, look through, remove, import, export.

Every failure reaches the user as one report line (self.report({'ERROR'}, ...)), never a traceback.
"""
import math
from typing import Any, Optional, Set

import bpy
import numpy as np
from bpy.props import FloatVectorProperty, IntProperty, StringProperty
from bpy_extras.io_utils import ExportHelper, ImportHelper
from mathutils import Matrix, Vector

from . import axes, exchange, model, preview

SAME_VIEW_COS = math.cos(math.radians(0.01))  # two keys this close in view (at one frame) are one


def _mesh_object(context: Any) -> Optional[Any]:
    obj = context.active_object
    return obj if obj is not None and obj.type == "MESH" else None


def _new_shape_key(obj: Any, name: str) -> Any:
    """A new shape key relative to the Basis (made when missing), a copy of the Basis."""
    if obj.data.shape_keys is None:
        obj.shape_key_add(name="Basis", from_mix=False)
    block = obj.shape_key_add(name=name or "key", from_mix=False)
    block.relative_key = obj.data.shape_keys.reference_key
    return block


def _key_frame(context: Any, obj: Any) -> int:
    return context.scene.frame_current if model.armature_animated(obj) else 0


def _check_view_free(obj: Any, view: np.ndarray, frame: int) -> None:
    for k in obj.vdg.keys:
        if k.frame == frame and float(np.dot(np.array(k.view), view)) >= SAME_VIEW_COS:
            raise model.AddonError(f"object '{obj.name}': key '{k.name}' already has this view"
                                   + (f" at frame {frame}" if frame else ""))


def _add_key(context: Any, obj: Any, name: str, view: np.ndarray) -> Any:
    frame = _key_frame(context, obj)
    _check_view_free(obj, view, frame)
    block = _new_shape_key(obj, name)
    item = obj.vdg.keys.add()
    item.name = block.name
    item.view = tuple(float(c) for c in view)
    item.frame = frame
    obj.vdg.active_index = len(obj.vdg.keys) - 1
    obj.active_shape_key_index = list(obj.data.shape_keys.key_blocks).index(block)
    return item


class _Reporting:
    """Runs `run()` and turns AddonError, ImportError and vdg's errors into one report line."""

    def execute(self, context: Any) -> Set[str]:
        try:
            return self.run(context)
        except Exception as e:  # the user sees one line; the handler style of the add-on
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}


class _OnKey(_Reporting):
    """An operator on one vdg key of the active mesh: `index`, or the panel's active key when -1."""

    @classmethod
    def poll(cls, context: Any) -> bool:
        obj = _mesh_object(context)
        return obj is not None and len(obj.vdg.keys) > 0

    def key_index(self, obj: Any) -> int:
        """The key this operator acts on; an AddonError naming the object when there is none."""
        index = self.index if self.index >= 0 else obj.vdg.active_index
        if not 0 <= index < len(obj.vdg.keys):
            raise model.AddonError(f"object '{obj.name}' has no key {index}")
        return index


class VDG_OT_key_from_camera(_Reporting, bpy.types.Operator):
    """New shape key for the active camera's view (the camera is stored as the key camera)"""

    bl_idname = "vdg.key_from_camera"
    bl_label = "New key from this camera"
    bl_options = {"REGISTER", "UNDO"}

    name: StringProperty(name="Name", default="")

    @classmethod
    def poll(cls, context: Any) -> bool:
        return _mesh_object(context) is not None

    def run(self, context: Any) -> Set[str]:
        obj = _mesh_object(context)
        cam = context.scene.camera
        if cam is None:
            raise model.AddonError("the scene has no active camera")
        world = cam.matrix_world
        view = model.view_from_eye(obj, world.translation)
        eye = model.eye_in_vdg(obj, world.translation)
        forward = model.eye_in_vdg(obj, world @ Vector((0.0, 0.0, -1.0))) - eye
        up = model.eye_in_vdg(obj, world @ Vector((0.0, 1.0, 0.0))) - eye
        distance = float(np.dot(model.center_of(obj) - eye, forward / np.linalg.norm(forward)))
        target = eye + forward / np.linalg.norm(forward) * (distance if distance > 1e-6 else 1.0)
        item = _add_key(context, obj, self.name or obj.vdg.new_key_name, view)
        item.has_camera = True
        item.camera.eye, item.camera.target = tuple(eye), tuple(target)
        item.camera.up = tuple(up / np.linalg.norm(up))
        item.camera.fov_deg = math.degrees(cam.data.angle_y) if cam.type == "CAMERA" else 40.0
        self.report({"INFO"}, f"key '{item.name}' at view {tuple(round(c, 4) for c in item.view)}")
        return {"FINISHED"}


class VDG_OT_key_from_view(_Reporting, bpy.types.Operator):
    """New shape key for a view direction (vdg axes, Y up, from the model's centre towards the eye)"""

    bl_idname = "vdg.key_from_view"
    bl_label = "New key from a view direction"
    bl_options = {"REGISTER", "UNDO"}

    name: StringProperty(name="Name", default="")
    direction: FloatVectorProperty(name="Direction", size=3, default=(0.0, 0.0, 0.0))

    @classmethod
    def poll(cls, context: Any) -> bool:
        return _mesh_object(context) is not None

    def run(self, context: Any) -> Set[str]:
        obj = _mesh_object(context)
        d = np.array(self.direction if any(self.direction) else obj.vdg.new_key_view, dtype=np.float64)
        n = float(np.linalg.norm(d))
        if not math.isfinite(n) or n < 1e-12:
            raise model.AddonError("the view direction is zero")
        item = _add_key(context, obj, self.name or obj.vdg.new_key_name, d / n)
        self.report({"INFO"}, f"key '{item.name}' at view {tuple(round(c, 4) for c in item.view)}")
        return {"FINISHED"}


def _look_at(eye: Vector, target: Vector, up: Vector) -> Matrix:
    """A camera's world rotation looking from eye at target (-Z forward, +Y up)."""
    forward = (target - eye).normalized()
    side = forward.cross(up)
    if side.length < 1e-9:
        side = forward.cross(Vector((0.0, 0.0, 1.0)) if abs(forward.z) < 0.9 else Vector((0.0, 1.0, 0.0)))
    side.normalize()
    true_up = side.cross(forward)
    return Matrix((side, true_up, -forward)).transposed().to_4x4()


def _framing_distance(obj: Any, center_local: Vector, fov_deg: float) -> float:
    """Distance (object space) at which a sphere around the whole mesh fits the field of view."""
    base = model.base_positions(obj)
    c = np.array(center_local)
    radius = float(np.sqrt(((base - c) ** 2).sum(axis=1)).max(initial=1.0))
    return 1.2 * radius / math.sin(math.radians(fov_deg) / 2.0)


class VDG_OT_look_through(_OnKey, bpy.types.Operator):
    """Puts the scene camera at the key camera (or on the key's view, framing the object)"""

    bl_idname = "vdg.look_through"
    bl_label = "Look through"
    bl_options = {"REGISTER", "UNDO"}

    index: IntProperty(name="Key", default=-1)

    def run(self, context: Any) -> Set[str]:
        obj = _mesh_object(context)
        index = self.key_index(obj)
        key = obj.vdg.keys[index]
        scene = context.scene
        cam = scene.camera
        if cam is None:
            cam = bpy.data.objects.new("vdg camera", bpy.data.cameras.new("vdg camera"))
            context.collection.objects.link(cam)
            scene.camera = cam
        center = Vector(axes.vec_to_blender(model.center_of(obj)))
        if key.has_camera:
            eye = Vector(axes.vec_to_blender(key.camera.eye))
            target = Vector(axes.vec_to_blender(key.camera.target))
            up = Vector(axes.vec_to_blender(key.camera.up))
            if cam.type == "CAMERA":
                cam.data.sensor_fit = "VERTICAL"
                cam.data.angle_y = math.radians(key.camera.fov_deg)
        else:
            fov = math.degrees(cam.data.angle_y) if cam.type == "CAMERA" else 40.0
            eye = center + Vector(axes.vec_to_blender(key.view)) * _framing_distance(obj, center, fov)
            target, up = center, Vector(axes.vec_to_blender((0.0, 1.0, 0.0)))
        mw = obj.matrix_world
        eye_w, target_w = mw @ eye, mw @ target
        up_w = (mw.to_3x3() @ up).normalized()
        rotation = _look_at(eye_w, target_w, up_w)
        cam.matrix_world = Matrix.Translation(eye_w) @ rotation
        if key.frame != 0 or model.armature_animated(obj):
            scene.frame_set(key.frame)
        obj.vdg.active_index = index
        context.view_layer.update()
        return {"FINISHED"}


class VDG_OT_remove_key(_OnKey, bpy.types.Operator):
    """Removes a vdg key and its shape key"""

    bl_idname = "vdg.remove_key"
    bl_label = "Remove key"
    bl_options = {"REGISTER", "UNDO"}

    index: IntProperty(name="Key", default=-1)

    def run(self, context: Any) -> Set[str]:
        obj = _mesh_object(context)
        index = self.key_index(obj)
        name = obj.vdg.keys[index].name
        obj.vdg.keys.remove(index)
        keys = obj.data.shape_keys
        block = keys.key_blocks.get(name) if keys is not None else None
        if block is not None:
            obj.shape_key_remove(block)
        obj.vdg.active_index = max(0, min(index, len(obj.vdg.keys) - 1))
        return {"FINISHED"}


class VDG_OT_refresh(_Reporting, bpy.types.Operator):
    """Sets the shape-key values from the active camera now (the live preview's step, once)"""

    bl_idname = "vdg.refresh"
    bl_label = "Preview once"

    def run(self, context: Any) -> Set[str]:
        preview.refresh(context.scene, force=True)
        if preview.errors:
            raise model.AddonError("; ".join(f"{k}: {v}" for k, v in preview.errors.items()))
        return {"FINISHED"}


class VDG_OT_import_model(_Reporting, bpy.types.Operator, ImportHelper):
    """Import a vdg model (manifest *.vdg.json or a glTF vdg exported) as a mesh with shape keys"""

    bl_idname = "vdg.import_model"
    bl_label = "Import vdg model"
    bl_options = {"REGISTER", "UNDO"}

    filename_ext = ".json"
    filter_glob: StringProperty(default="*.vdg.json;*.json;*.gltf;*.glb", options={"HIDDEN"})

    def run(self, context: Any) -> Set[str]:
        obj = exchange.import_model(context, self.filepath)
        self.report({"INFO"}, f"imported '{obj.name}': {len(obj.data.vertices)} vertices, "
                              f"{len(obj.vdg.keys)} keys")
        return {"FINISHED"}


class VDG_OT_export_model(_Reporting, bpy.types.Operator, ExportHelper):
    """Export the active object's vdg model: a manifest (.vdg.json + OBJ files) or glTF (.gltf/.glb)"""

    bl_idname = "vdg.export_model"
    bl_label = "Export vdg model"

    filename_ext = ".vdg.json"
    check_extension = None  # the extension picks the format: .vdg.json, .gltf or .glb
    filter_glob: StringProperty(default="*.vdg.json;*.gltf;*.glb", options={"HIDDEN"})

    @classmethod
    def poll(cls, context: Any) -> bool:
        obj = _mesh_object(context)
        return obj is not None and len(obj.vdg.keys) > 0

    def run(self, context: Any) -> Set[str]:
        obj = _mesh_object(context)
        m = exchange.export_model(context, obj, self.filepath)
        self.report({"INFO"}, f"wrote {self.filepath}: {len(m.keys)} keys"
                              + (f", {m.frame_count} frames" if m.animated else ""))
        return {"FINISHED"}


CLASSES = (VDG_OT_key_from_camera, VDG_OT_key_from_view, VDG_OT_look_through, VDG_OT_remove_key,
           VDG_OT_refresh, VDG_OT_import_model, VDG_OT_export_model)


def _menu_import(self: Any, context: Any) -> None:
    self.layout.operator(VDG_OT_import_model.bl_idname, text="vdg model (.vdg.json, .gltf, .glb)")


def _menu_export(self: Any, context: Any) -> None:
    self.layout.operator(VDG_OT_export_model.bl_idname, text="vdg model (.vdg.json, .gltf, .glb)")


def register() -> None:
    """Registers the operators and their File > Import/Export entries."""
    for cls in CLASSES:
        bpy.utils.register_class(cls)
    bpy.types.TOPBAR_MT_file_import.append(_menu_import)
    bpy.types.TOPBAR_MT_file_export.append(_menu_export)


def unregister() -> None:
    """Removes the menu entries and operators."""
    bpy.types.TOPBAR_MT_file_export.remove(_menu_export)
    bpy.types.TOPBAR_MT_file_import.remove(_menu_import)
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
