"""Live preview: every object with vdg keys gets its shape-key values from the active camera.

Handlers on depsgraph_update_post and frame_change_post. Each object has its own view (the camera
carried into the object's local space, vdg axes), so moved, rotated, scaled objects and every member
of a crowd blend for where the camera sees them from. A value is written only when it changes by more
than WRITE_EPS, and a module flag stops the handler from re-entering through its own writes.
"""
import contextlib
import math
from typing import Any, Dict, Iterator, Optional

import bpy
from bpy.app.handlers import persistent

from . import model

WRITE_EPS = 1e-7  # a shape-key value changing less than this is not written (no update loop)

_busy = False
errors: Dict[str, str] = {}  # object name -> the last preview error, shown in the panel


@contextlib.contextmanager
def suspended() -> Iterator[None]:
    """Runs a block (export's frame stepping) without the preview writing values."""
    global _busy
    old, _busy = _busy, True
    try:
        yield
    finally:
        _busy = old


def object_weights(obj: Any, scene: Any, camera: Any) -> Dict[str, float]:
    """The shape-key values of `obj` seen from `camera` at the scene's frame: model.weights(view)["keys"].

    Animated models (section 4) give view weight x time coefficient at the current frame, which can
    leave [0, 1].
    """
    m = model.CACHE.get(obj, scene)
    eye = model.eye_in_vdg(obj, camera.matrix_world.translation)
    view = m.view_from_eye(eye)
    if m.animated:
        first, _ = model.frame_range(scene, obj)
        return dict(m.weights(view, frame=float(scene.frame_current - first))["keys"])
    return dict(m.weights(view)["keys"])


def apply_weights(obj: Any, weights: Dict[str, float]) -> int:
    """Writes the values (widening slider_min/max when needed); returns how many changed."""
    blocks = obj.data.shape_keys.key_blocks
    changed = 0
    for name, value in weights.items():
        block = blocks.get(name)
        if block is None or not math.isfinite(value):
            continue
        if value < block.slider_min:
            block.slider_min = max(-10.0, math.floor(value))
        if value > block.slider_max:
            block.slider_max = min(10.0, math.ceil(value))
        if abs(block.value - value) > WRITE_EPS:
            block.value = value
            changed += 1
    return changed


def refresh(scene: Any, force: bool = False) -> int:
    """Sets the values of every vdg object of the scene (when the preview is on, or `force`).

    Returns how many values changed; an object's error goes to `errors` (the panel shows it).
    """
    global _busy
    if _busy or scene is None or not (force or scene.vdg_live_preview) or scene.camera is None:
        return 0
    _busy = True
    changed = 0
    try:
        for obj in scene.objects:
            if obj.type != "MESH" or not obj.vdg.keys or not obj.vdg.preview or obj.data.shape_keys is None:
                continue
            try:
                changed += apply_weights(obj, object_weights(obj, scene, scene.camera))
                errors.pop(obj.name, None)
            except Exception as e:  # shown in the panel; a handler must not raise
                errors[obj.name] = str(e)
    finally:
        _busy = False
    return changed


def request_refresh(scene: Optional[Any]) -> None:
    """A setting changed: refresh now (the cache notices the change through its signature)."""
    if scene is not None:
        refresh(scene)


@persistent
def _on_depsgraph(scene: Any, depsgraph: Any = None) -> None:
    refresh(scene)


@persistent
def _on_frame(scene: Any, depsgraph: Any = None) -> None:
    refresh(scene)


@persistent
def _on_load(*_args: Any) -> None:
    model.CACHE.clear()
    errors.clear()


HANDLERS = ((bpy.app.handlers.depsgraph_update_post, _on_depsgraph),
            (bpy.app.handlers.frame_change_post, _on_frame),
            (bpy.app.handlers.load_post, _on_load))


def register() -> None:
    """Adds the handlers (once)."""
    for handlers, fn in HANDLERS:
        if fn not in handlers:
            handlers.append(fn)


def unregister() -> None:
    """Removes the handlers and forgets the cached models."""
    for handlers, fn in HANDLERS:
        while fn in handlers:
            handlers.remove(fn)
    model.CACHE.clear()
    errors.clear()
