"""Takes docs/blender.md's screenshots: Blender with its UI, Spot imported, the vdg sidebar tab open.

xvfb-run -s "-screen 0 1600x1000x24" blender --factory-startup --enable-event-simulate --python blender/screenshots.py -- OUT_DIR SPOT
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
SIZE = (1120, 700)
TAB_FROM_RIGHT, TAB_FROM_TOP = int(os.environ.get("TAB_X", "14")), int(os.environ.get("TAB_Y", "157"))


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
    for area in bpy.context.window.screen.areas:  # the Properties editor shows the shape-key values
        if area.type == "PROPERTIES":
            area.spaces.active.context = "DATA"
    obj.vdg.active_index = 1
    bpy.ops.vdg.look_through(index=1)


def _tab_point():
    region = next(r for r in view3d().regions if r.type == "UI")
    return region.x + region.width - TAB_FROM_RIGHT, region.y + region.height - TAB_FROM_TOP


def close_splash():
    """A click in the 3D view's header closes the splash screen, which would swallow the tab's click."""
    bpy.context.window.event_simulate(type="LEFTMOUSE", value="PRESS", x=600, y=960)
    bpy.context.window.event_simulate(type="LEFTMOUSE", value="RELEASE", x=600, y=960)


def hover_tab():
    """Moves the simulated mouse onto the sidebar's "vdg" tab (one event loop before the click)."""
    x, y = _tab_point()
    bpy.context.window.event_simulate(type="MOUSEMOVE", value="NOTHING", x=x, y=y)


def open_tab():
    """Clicks the sidebar's "vdg" tab (Blender 3.4 has no API for the active tab: the window runs with
    --enable-event-simulate, and the tab is the last one, below Item, Tool and View)."""
    window = bpy.context.window
    x, y = _tab_point()
    window.event_simulate(type="LEFTMOUSE", value="PRESS", x=x, y=y)
    window.event_simulate(type="LEFTMOUSE", value="RELEASE", x=x, y=y)


def shot(name):
    def take():
        path = os.path.join(OUT, name)
        settings = bpy.context.scene.render.image_settings
        settings.file_format, settings.color_mode, settings.compression = "PNG", "RGB", 100
        bpy.ops.screen.screenshot(filepath=path)
        image = bpy.data.images.load(path)  # scaled down: each picture under 300 KB
        image.scale(*SIZE)
        image.save_render(path, scene=bpy.context.scene)  # the scene's PNG settings: compression 100
        bpy.data.images.remove(image)
        print(f"wrote {path} ({os.path.getsize(path) // 1024} KB)")
    return take


def between():
    cam = bpy.context.scene.camera
    obj = bpy.context.view_layer.objects.active
    centre = obj.matrix_world @ Vector((0.0, -0.19, 0.11))
    cam.location = centre + Vector((-2.2, 1.4, 1.3)) * 1.7
    direction = centre - cam.location
    cam.rotation_euler = direction.to_track_quat("-Z", "Y").to_euler()
    bpy.context.view_layer.update()


def step():
    if not STEPS:
        bpy.ops.wm.quit_blender()
        return None
    try:
        STEPS.pop(0)()
    except Exception as e:  # a failed step still ends Blender
        print(f"screenshots: {e}")
        STEPS.clear()
    return 0.7


STEPS[:] = [setup, close_splash, hover_tab, open_tab, shot("blender_panel.png"), between, shot("blender_preview.png")]
bpy.app.timers.register(step, first_interval=2.0)
