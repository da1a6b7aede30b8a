"""Takes docs/blender.md's screenshots: Blender with its UI, Spot imported, the vdg sidebar tab open.

xvfb-run -s "-screen 0 1600x1000x24" blender --factory-startup --python blender/screenshots.py -- OUT_DIR SPOT
(with the add-on importable: PYTHONPATH=blender:BUILD/python). Writes OUT_DIR/blender_panel.png (the panel
with Spot's keys, looking through a key) and OUT_DIR/blender_preview.png (the camera between keys, the
live preview blending them), then quits.
"""
import math
import os
import sys

import bpy
from mathutils import Vector

OUT, SPOT = sys.argv[sys.argv.index("--") + 1:][:2]
STEPS = []


def view3d():
    for area in bpy.context.window.screen.areas:
        if area.type == "VIEW_3D":
            return area
    raise RuntimeError("no 3D view")


def setup():
    import vdg_addon
    vdg_addon.register()
    for name in [o.name for o in bpy.data.objects if o.type != "CAMERA"]:
        bpy.data.objects.remove(bpy.data.objects[name])
    bpy.ops.vdg.import_model(filepath=SPOT)
    obj = bpy.context.view_layer.objects.active
    obj.rotation_euler = (0.0, 0.0, math.radians(180.0))  # Spot faces the default camera
    scene = bpy.context.scene
    scene.vdg_live_preview = True
    area = view3d()
    space = area.spaces.active
    space.show_region_ui = True
    space.shading.type = "SOLID"
    space.shading.color_type = "TEXTURE"
    space.region_3d.view_perspective = "CAMERA"
    obj.vdg.active_index = 1
    bpy.ops.vdg.look_through(index=1)


def open_tab():
    for region in view3d().regions:
        if region.type == "UI":
            region.width  # drawn once: the categories exist now
            region.active_panel_category = "vdg"
    for area in bpy.context.window.screen.areas:
        area.tag_redraw()


def shot(name):
    def take():
        path = os.path.join(OUT, name)
        with bpy.context.temp_override(window=bpy.context.window, area=view3d()):
            bpy.ops.screen.screenshot_area(filepath=path)
        print(f"wrote {path}")
    return take


def between():
    cam = bpy.context.scene.camera
    obj = bpy.context.view_layer.objects.active
    centre = obj.matrix_world @ Vector((0.0, -0.19, 0.11))
    cam.location = centre + Vector((-2.2, 1.4, 1.3))
    direction = centre - cam.location
    cam.rotation_euler = direction.to_track_quat("-Z", "Y").to_euler()
    bpy.context.view_layer.update()


def step():
    if not STEPS:
        bpy.ops.wm.quit_blender()
        return None
    STEPS.pop(0)()
    return 1.5


STEPS[:] = [setup, open_tab, shot("blender_panel.png"), between, open_tab, shot("blender_preview.png")]
bpy.app.timers.register(step, first_interval=2.0)
