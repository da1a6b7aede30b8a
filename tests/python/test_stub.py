"""python/vdg.pyi names exactly what the module has, and every public function has a docstring."""
from __future__ import annotations

import ast

import vdg
from conftest import SOURCE_DIR


def stub_names() -> dict[str, set[str]]:
    """Top-level names ("") and each class's members, as python/vdg.pyi declares them."""
    tree = ast.parse((SOURCE_DIR / "python" / "vdg.pyi").read_text())
    names: dict[str, set[str]] = {"": set()}
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            names[""].add(node.name)
        if isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            names[""].add(node.target.id)
        if isinstance(node, ast.ClassDef):
            names[node.name] = {n.name for n in node.body if isinstance(n, ast.FunctionDef)} - {"__init__"}
    return names


def public(obj: object) -> set[str]:
    return {n for n in dir(obj) if not n.startswith("_")}


def test_stub_matches_module() -> None:
    names = stub_names()
    assert names[""] == public(vdg) | {"__version__"}
    for cls in ("Camera", "Key", "ViewSphere", "Model"):
        assert names[cls] == public(getattr(vdg, cls)), cls
    assert names["Error"] == set()


def test_docstrings() -> None:
    for name in ("load", "build"):
        assert getattr(vdg, name).__doc__
    for cls in (vdg.Camera, vdg.Key, vdg.ViewSphere, vdg.Model):
        assert cls.__doc__
        for member in public(cls):
            assert getattr(cls, member).__doc__, f"{cls.__name__}.{member}"
