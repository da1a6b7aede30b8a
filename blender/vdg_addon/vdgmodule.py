"""Finds `import vdg`: the copy inside this add-on's folder (the zip carries it) or PYTHONPATH's."""
import glob
import importlib
import os
import sys
from types import ModuleType
from typing import Optional

_ADDON_DIR = os.path.dirname(os.path.abspath(__file__))
_module: Optional[ModuleType] = None


def get() -> ModuleType:
    """Returns the vdg extension module, importing it on first use.

    A `vdg.cpython-*.so` next to this file wins (its folder goes first on sys.path); otherwise
    `vdg` is imported from sys.path as it is (PYTHONPATH=BUILD/python). Raises ImportError with a
    line that says where the module was looked for.
    """
    global _module
    if _module is not None:
        return _module
    if glob.glob(os.path.join(_ADDON_DIR, "vdg.cpython-*.so")) and _ADDON_DIR not in sys.path:
        sys.path.insert(0, _ADDON_DIR)
    try:
        _module = importlib.import_module("vdg")
    except ImportError as e:
        raise ImportError(
            f"the vdg Python module is not available ({e}); install the add-on from the zip the build "
            f"writes (BUILD/blender/vdg_addon.zip) or start Blender with PYTHONPATH=BUILD/python") from e
    return _module
