"""vdg's model space is Y up, Blender's Z up; the add-on maps them as Blender's glTF I/O does.

vdg (x, y, z) -> Blender (x, -z, y) and Blender (x, y, z) -> vdg (x, z, -y): a rotation, so
lengths, angles and handedness are kept, and the maps are exact in float arithmetic.
"""
from typing import Sequence, Tuple

import numpy as np


def to_vdg(points: np.ndarray) -> np.ndarray:
    """Blender positions (N, 3) -> vdg model space (N, 3) float32, C-contiguous."""
    p = np.asarray(points, dtype=np.float32).reshape(-1, 3)
    return np.ascontiguousarray(np.stack([p[:, 0], p[:, 2], -p[:, 1]], axis=1))


def to_blender(points: np.ndarray) -> np.ndarray:
    """vdg model space (N, 3) -> Blender positions (N, 3) float32, C-contiguous."""
    p = np.asarray(points, dtype=np.float32).reshape(-1, 3)
    return np.ascontiguousarray(np.stack([p[:, 0], -p[:, 2], p[:, 1]], axis=1))


def vec_to_vdg(v: Sequence[float]) -> Tuple[float, float, float]:
    """One Blender vector -> a vdg one, in double precision."""
    return (float(v[0]), float(v[2]), -float(v[1]))


def vec_to_blender(v: Sequence[float]) -> Tuple[float, float, float]:
    """One vdg vector -> a Blender one, in double precision."""
    return (float(v[0]), -float(v[2]), float(v[1]))
