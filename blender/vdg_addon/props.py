"""The data the add-on keeps on a mesh object (`obj.vdg`) and on the scene (`scene.vdg_live_preview`).

Every vector here is in vdg's axes (Y up, see axes.py) and the object's local space, so a key's
view survives moving, rotating or scaling the object (and every member of a crowd has its own).
"""
import bpy
from bpy.props import (BoolProperty, CollectionProperty, EnumProperty, FloatProperty,
                       FloatVectorProperty, IntProperty, PointerProperty, StringProperty)
from bpy.types import PropertyGroup

UNCOVERED_ITEMS = [
    ("base", "Base", "Outside the keys' hull the base mesh takes over (vdg's default)"),
    ("cosine", "Cosine", "Outside the hull the nearest keys fade with the cosine of the angle"),
    ("cosine2", "Cosine squared", "Outside the hull the nearest keys fade with the squared cosine"),
]

SCHEME_ITEMS = [
    ("linear", "Linear", "The paper's barycentric blend of the view's hull triangle (section 3.2.2)"),
    ("smooth", "Smooth", "A C1 blend of the view's hull triangle (docs/weights.md)"),
    ("rbf", "RBF", "Radial basis functions over every key (docs/weights.md, 'The rbf scheme')"),
]
KERNEL_ITEMS = [
    ("gaussian", "Gaussian", "exp(-s^2) of the chord over the width's chord"),
    ("inverse-multiquadric", "Inverse multiquadric", "1 / sqrt(1 + s^2)"),
    ("wendland", "Wendland", "Compactly supported: keys beyond the width do not move a view"),
]


def _refresh(self, context) -> None:
    """Property update: the preview rebuilds its model and sets the values again."""
    from . import preview

    preview.request_refresh(context.scene if context else None)


def _toggle_preview(self, context) -> None:
    """Scene toggle: sets the values now when switched on."""
    from . import preview

    preview.request_refresh(self)


class VdgCamera(PropertyGroup):
    """A key camera, vdg axes, object space: eye, target, up and vertical field of view."""

    eye: FloatVectorProperty(name="Eye", size=3, subtype="XYZ")
    target: FloatVectorProperty(name="Target", size=3, subtype="XYZ")
    up: FloatVectorProperty(name="Up", size=3, default=(0.0, 1.0, 0.0), subtype="XYZ")
    fov_deg: FloatProperty(name="Field of view", default=40.0, min=0.001, max=179.0)


class VdgKey(PropertyGroup):
    """One key of the model: `name` is its shape key's name."""

    view: FloatVectorProperty(name="View", size=3, subtype="XYZ", update=_refresh,
                              description="Unit direction from the model's centre towards the key's eye (vdg axes, Y up)")
    frame: IntProperty(name="Frame", default=0, update=_refresh,
                       description="Scene frame of the key on an animated mesh (section 4); 0 when static")
    has_camera: BoolProperty(name="Has camera", default=False)
    camera: PointerProperty(type=VdgCamera)


class VdgObjectSettings(PropertyGroup):
    """`obj.vdg`: the keys and the model's settings."""

    keys: CollectionProperty(type=VdgKey)
    active_index: IntProperty(name="Active key", default=0)
    new_key_name: StringProperty(name="Name", default="key", description="Name of the next key's shape key")
    new_key_view: FloatVectorProperty(name="View", size=3, default=(0.0, 0.0, 1.0), subtype="XYZ",
                                      description="View direction of the next key (vdg axes, Y up)")
    sharpness: FloatProperty(name="Sharpness", default=1.0, min=1e-3, soft_max=8.0, update=_refresh,
                             description="Alpha of the paper's section 3.2.2: higher keeps each key longer")
    uncovered: EnumProperty(name="Uncovered", items=UNCOVERED_ITEMS, default="base", update=_refresh,
                            description="What views outside the keys' convex hull see")
    scheme: EnumProperty(name="Weights", items=SCHEME_ITEMS, default="linear", update=_refresh,
                         description="How a view's key weights are computed (docs/weights.md)")
    rbf_kernel: EnumProperty(name="Kernel", items=KERNEL_ITEMS, default="gaussian", update=_refresh,
                             description="The rbf scheme's radial kernel")
    rbf_width: FloatProperty(name="Width", default=60.0, min=0.001, max=180.0, update=_refresh,
                             description="The rbf scheme's kernel width (degrees on the viewing sphere)")
    base_falloff_deg: FloatProperty(name="Base falloff", default=60.0, min=0.001, max=180.0, update=_refresh,
                                    description="Angle (degrees) over which the base takes over outside the hull")
    use_center: BoolProperty(name="Centre", default=False, update=_refresh,
                             description="Measure views from this centre (otherwise the base's bounding-box centre)")
    center: FloatVectorProperty(name="Centre", size=3, subtype="XYZ", update=_refresh)
    preview: BoolProperty(name="Preview", default=True, update=_refresh,
                          description="Let the live preview set this object's shape-key values")
    loop: BoolProperty(name="Loop", default=False, update=_refresh,
                       description="The animation loops (keys' time interpolation wraps around)")
    fps: FloatProperty(name="FPS", default=24.0, min=0.001)
    frame_count: IntProperty(name="Frames", default=0, min=0, update=_refresh,
                             description="Frames of the base animation (0: the scene's frame range)")
    comment: StringProperty(name="Comment", default="")


CLASSES = (VdgCamera, VdgKey, VdgObjectSettings)


def register() -> None:
    """Registers the property groups and attaches them to Object and Scene."""
    for cls in CLASSES:
        bpy.utils.register_class(cls)
    bpy.types.Object.vdg = PointerProperty(type=VdgObjectSettings)
    bpy.types.Scene.vdg_live_preview = BoolProperty(
        name="Live preview", default=False, update=_toggle_preview,
        description="Set every vdg object's shape-key values from the active camera")


def unregister() -> None:
    """Removes the properties and classes register() added."""
    del bpy.types.Scene.vdg_live_preview
    del bpy.types.Object.vdg
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
