"""vdg: view-dependent shape keys in Blender (Rademacher, SIGGRAPH 99).

A mesh's shape keys become the key deformations of a vdg view-dependent model: each key is
tied to a view direction (and, on an armature-animated mesh, a frame; the paper's section 4),
the live preview sets every shape key's value from the active camera through `import vdg`, and
the object imports from and exports to vdg's manifest and glTF. See docs/blender.md.
"""
bl_info = {
    "name": "vdg: view-dependent geometry",
    "author": "vdg",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "View3D > Sidebar > vdg; File > Import/Export > vdg model",
    "description": "Shape keys tied to view directions (Rademacher 99), live camera preview, vdg manifest/glTF",
    "category": "Object",
}

if "bpy" in locals():  # a reload (F8 / addon_utils) re-imports the submodules
    import importlib

    for _module in (axes, vdgmodule, props, model, preview, exchange, operators, ui):  # noqa: F821
        importlib.reload(_module)
else:
    from . import axes, vdgmodule, props, model, preview, exchange, operators, ui

import bpy  # noqa: E402,F401


def register() -> None:
    """Registers the properties, operators, panel, menu entries and preview handlers."""
    props.register()
    operators.register()
    ui.register()
    preview.register()


def unregister() -> None:
    """Removes everything register() added, in reverse order."""
    preview.unregister()
    ui.unregister()
    operators.unregister()
    props.unregister()
