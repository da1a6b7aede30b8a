"""The vdg panel in the 3D view's sidebar (N panel, tab "vdg") for a mesh object."""
from typing import Any

import bpy

from . import preview


class VDG_UL_keys(bpy.types.UIList):
    """One row per key: name, view direction (vdg axes), frame, look-through button."""

    def draw_item(self, context: Any, layout: Any, data: Any, item: Any, icon: Any, active_data: Any,
                  active_propname: str, index: int = 0) -> None:
        split = layout.split(factor=0.5, align=True)
        split.label(text=item.name, icon="CAMERA_DATA" if item.has_camera else "ORIENTATION_VIEW")
        row = split.row(align=True)
        v = item.view
        row.label(text=f"{v[0]:.1f},{v[1]:.1f},{v[2]:.1f}" + (f" f{item.frame}" if item.frame else ""))
        op = row.operator("vdg.look_through", text="", icon="HIDE_OFF")
        op.index = index


class VDG_PT_panel(bpy.types.Panel):
    """View-dependent shape keys of the active mesh object."""

    bl_label = "View-dependent keys"
    bl_idname = "VDG_PT_panel"
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "vdg"

    @classmethod
    def poll(cls, context: Any) -> bool:
        return context.active_object is not None and context.active_object.type == "MESH"

    def draw(self, context: Any) -> None:
        layout = self.layout
        obj = context.active_object
        s = obj.vdg
        scene = context.scene
        row = layout.row(align=True)
        row.prop(scene, "vdg_live_preview", toggle=True, icon="VIEW_CAMERA")
        row.operator("vdg.refresh", text="", icon="FILE_REFRESH")
        if scene.camera is None:
            layout.label(text="The scene has no active camera", icon="ERROR")
        if obj.name in preview.errors:
            layout.label(text=preview.errors[obj.name], icon="ERROR")

        box = layout.box()
        box.prop(s, "new_key_name")
        box.operator("vdg.key_from_camera", icon="CAMERA_DATA").name = s.new_key_name
        row = box.row(align=True)
        row.prop(s, "new_key_view", text="")
        row.operator("vdg.key_from_view", text="From view", icon="ORIENTATION_VIEW").name = s.new_key_name

        layout.label(text=f"Key views ({len(s.keys)})")
        row = layout.row()
        row.template_list("VDG_UL_keys", "", s, "keys", s, "active_index", rows=4)
        col = row.column(align=True)
        col.operator("vdg.look_through", text="", icon="HIDE_OFF").index = -1
        col.operator("vdg.remove_key", text="", icon="REMOVE").index = -1
        if 0 <= s.active_index < len(s.keys):
            key = s.keys[s.active_index]
            col = layout.column(align=True)
            col.prop(key, "view")
            col.prop(key, "frame")

        col = layout.column(align=True)
        col.prop(s, "sharpness")
        col.prop(s, "uncovered")
        col.prop(s, "scheme")
        if s.scheme == "rbf":
            col.prop(s, "rbf_kernel")
            col.prop(s, "rbf_width")
        if s.uncovered == "base":
            col.prop(s, "base_falloff_deg")
        col.prop(s, "preview")
        row = layout.row(align=True)
        row.prop(s, "use_center")
        if s.use_center:
            row.prop(s, "center", text="")
        row = layout.row(align=True)
        row.prop(s, "loop")
        row.prop(s, "frame_count")
        row = layout.row(align=True)
        row.operator("vdg.import_model", text="Import", icon="IMPORT")
        row.operator("vdg.export_model", text="Export", icon="EXPORT")


CLASSES = (VDG_UL_keys, VDG_PT_panel)


def register() -> None:
    """Registers the list and the panel."""
    for cls in CLASSES:
        bpy.utils.register_class(cls)


def unregister() -> None:
    """Removes the list and the panel."""
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
