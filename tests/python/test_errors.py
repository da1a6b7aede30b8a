"""Every invalid input to `import vdg` raises the right exception with a message that names what
is wrong (vdg.Error with vdg's own line, ValueError, TypeError), and nothing crashes."""
from __future__ import annotations

import pathlib

import numpy as np
import pytest

import vdg
from conftest import EXAMPLES, MODELS


def tiny_mesh() -> tuple[np.ndarray, np.ndarray]:
    """A tetrahedron: 4 vertices, 4 triangles."""
    base = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=np.float32)
    triangles = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]], dtype=np.int32)
    return base, triangles


def test_load_errors(tmp_path: pathlib.Path) -> None:
    with pytest.raises(vdg.Error, match="missing.vdg.json"):
        vdg.load(tmp_path / "missing.vdg.json")
    with pytest.raises(vdg.Error, match="an OBJ mesh, not a view-dependent model"):
        vdg.load(EXAMPLES / "spot" / "spot.obj")
    broken = tmp_path / "broken.vdg.json"
    broken.write_text('{"version": 2, "base": "nothing.obj", "keys": []}')
    with pytest.raises(vdg.Error, match="broken.vdg.json"):
        vdg.load(broken)
    with pytest.raises(TypeError, match="path"):
        vdg.load(42)
    with pytest.raises(TypeError, match="bytes"):
        vdg.load(b"spot.vdg.json")


def test_plain_gltf_is_not_a_model(tmp_path: pathlib.Path) -> None:
    """A glTF file without vdg's description (here: the walker's animated base) is refused."""
    with pytest.raises(vdg.Error, match="walker.glb"):
        vdg.load(EXAMPLES / "walk" / "walker.glb")


@pytest.mark.parametrize("view, exception, message", [
    ([1.0, 2.0], ValueError, r"view: expected shape \(3,\), got \(2,\)"),
    ([[1.0, 2.0, 3.0]], ValueError, r"view: expected shape \(3,\), got \(1, 3\)"),
    ([0.0, 0.0, 0.0], ValueError, "view: expected a non-zero direction"),
    ([np.nan, 0.0, 1.0], ValueError, "view: expected finite numbers"),
    ([np.inf, 0.0, 1.0], ValueError, "view: expected finite numbers"),
    (["a", "b", "c"], TypeError, "view: expected an array of numbers, got dtype <U1"),
    (np.array([1, None, 2], dtype=object), TypeError, "view: expected an array of numbers, got dtype object"),
    ([1j, 0, 1], TypeError, "view: expected an array of numbers, got dtype complex128"),
    (None, TypeError, "view: expected an array of numbers, got None"),
    ("xyz", TypeError, "view: expected an array of numbers"),
])
def test_bad_views(view: object, exception: type, message: str) -> None:
    model = vdg.load(MODELS["head"])
    with pytest.raises(exception, match=message):
        model.weights(view)
    with pytest.raises(exception, match=message):
        model.evaluate(view)


def test_integer_views_are_converted() -> None:
    model = vdg.load(MODELS["head"])
    assert model.weights(np.array([0, 0, 2], dtype=np.int64)) == model.weights([0.0, 0.0, 1.0])


def test_sharpness_and_frame_errors(models: dict[str, vdg.Model]) -> None:
    head, walker = models["head"], models["walker"]
    for bad in (0.0, -1.0):
        with pytest.raises(ValueError, match="sharpness: expected a number > 0"):
            head.weights([0, 0, 1], sharpness=bad)
    with pytest.raises(ValueError, match="sharpness: expected a finite number"):
        head.weights([0, 0, 1], sharpness=float("nan"))
    with pytest.raises(TypeError, match="sharpness: expected a number"):
        head.weights([0, 0, 1], sharpness="sharp")
    with pytest.raises(ValueError, match="frame: the model is not animated"):
        head.evaluate([0, 0, 1], frame=1)
    with pytest.raises(ValueError, match=r"frame: the model is animated \(40 frames\)"):
        walker.evaluate([0, 0, 1])
    for frame in (-1, 40, 10**30):
        with pytest.raises(ValueError, match="frame"):
            walker.evaluate([0, 0, 1], frame=frame)
    with pytest.raises(TypeError, match="frame: expected an int"):
        walker.evaluate([0, 0, 1], frame=1.5)
    with pytest.raises(ValueError, match="frame: expected a finite number"):
        walker.weights([0, 0, 1], frame=float("inf"))
    with pytest.raises(ValueError, match="time_coefficients: the model is not animated"):
        head.time_coefficients(0, 1.0)
    with pytest.raises(ValueError, match="view_index: expected a view in 0..1, got 2"):
        walker.time_coefficients(2, 1.0)
    with pytest.raises(ValueError, match="eye: the eye is at the model's centre"):
        head.view_from_eye(head.center)


def test_build_shape_and_dtype_errors() -> None:
    base, tris = tiny_mesh()
    key = {"name": "k", "positions": base * 1.1, "view": [0, 0, 1]}
    cases = [
        (lambda: vdg.build(base[:, :2], tris, [key]), ValueError, r"base: expected shape \(N, 3\), got \(4, 2\)"),
        (lambda: vdg.build(base, tris[:, :2], [key]), ValueError, r"triangles: expected shape \(N, 3\), got \(4, 2\)"),
        (lambda: vdg.build(base, tris.astype(np.float32), [key]), TypeError, "triangles: expected integers"),
        (lambda: vdg.build(base, tris - 1, [key]), ValueError, "triangles: value -1"),
        (lambda: vdg.build(base, tris + 10, [key]), vdg.Error, "build: base"),
        (lambda: vdg.build(base.astype(str), tris, [key]), TypeError, "base: expected an array of numbers"),
        (lambda: vdg.build(base, tris, [dict(key, positions=base[:3])]), ValueError,
         r"key 'k': positions: expected shape \(4, 3\)"),
        (lambda: vdg.build(base, tris, [dict(key, view=[0, 0, 0])]), ValueError, "key 'k': view: expected a non-zero"),
        (lambda: vdg.build(base, tris, [dict(key, colour=1)]), ValueError, "keys\\[0\\]: unknown field 'colour'"),
        (lambda: vdg.build(base, tris, [{"positions": base, "view": [0, 0, 1]}]), TypeError, "'name' must be a str"),
        (lambda: vdg.build(base, tris, [key, dict(key, view=[1, 0, 0])]), vdg.Error, "another key has the same name"),
        (lambda: vdg.build(base, tris, [key, dict(key, name="j")]), vdg.Error, "same view"),
        (lambda: vdg.build(base, tris, [key], uncovered="nowhere"), ValueError,
         "uncovered: expected 'base', 'cosine' or 'cosine2', got 'nowhere'"),
        (lambda: vdg.build(base, tris, [key], sharpness=-2.0), vdg.Error, "sharpness"),
        (lambda: vdg.build(base, tris, []), vdg.Error, "key"),
        (lambda: vdg.build(base, tris, "keys"), TypeError, "keys: expected a list"),
        (lambda: vdg.build(base, tris, [42]), TypeError, "keys\\[0\\]: expected a vdg.Key or a dict"),
        (lambda: vdg.build(base, tris, [dict(key, positions=np.full((4, 3), np.nan))]), vdg.Error, "finite"),
        (lambda: vdg.build(base, tris, [key], center=[0, 0]), ValueError, r"center: expected shape \(3,\)"),
        (lambda: vdg.build(base, tris, [key], uvs=np.zeros((3, 2))), ValueError, r"uvs: expected shape \(4, 2\)"),
        (lambda: vdg.build(base, tris, [key], corner_uvs=np.zeros((4, 2))), ValueError,
         r"corner_uvs: expected shape \(4, 3, 2\)"),
        (lambda: vdg.build(base, tris, [key], uvs=np.zeros((4, 2)), corner_uvs=np.zeros((4, 3, 2))), ValueError,
         "give one of them"),
        (lambda: vdg.build(base, tris, [key], materials=[{}]), ValueError, "materials, face_materials: give both"),
        (lambda: vdg.build(base, tris, [key], materials=[{}], face_materials=[0, 0, 1, 0]), ValueError,
         r"face_materials\[2\]: expected -1 \(none\) or a material index below 1, got 1"),
        (lambda: vdg.build(base, tris, [key], materials=[{"base_color": (2, 0, 0)}], face_materials=[0] * 4),
         ValueError, r"materials\[0\].base_color: expected display RGB values in \[0, 1\]"),
        (lambda: vdg.build(base, tris, [key], materials=[{"texture": b"not an image"}], face_materials=[0] * 4),
         vdg.Error, r"materials\[0\].texture"),
        (lambda: vdg.build(base, tris, [key], materials=[{"texture": "a.png"}], face_materials=[0] * 4),
         TypeError, r"materials\[0\].texture: expected the bytes"),
        (lambda: vdg.build(base, tris, [key], materials=["red"], face_materials=[0] * 4), TypeError,
         r"materials\[0\]: expected a dict"),
    ]
    for call, exception, message in cases:
        with pytest.raises(exception, match=message):
            call()


def test_build_animated_errors() -> None:
    base, tris = tiny_mesh()
    frames = np.stack([base, base + 0.1, base + 0.2])
    key = {"name": "k", "positions": base * 1.1, "view": [0, 0, 1], "frame": 1}
    assert vdg.build(None, tris, [key], frames=frames).frame_count == 3
    with pytest.raises(ValueError, match=r"frames: expected shape \(F, 4, 3\)"):
        vdg.build(base, tris, [key], frames=frames[:, :2])
    with pytest.raises(ValueError, match="base: differs from frames\\[0\\]"):
        vdg.build(base + 1, tris, [key], frames=frames)
    with pytest.raises(vdg.Error, match="frame"):
        vdg.build(base, tris, [dict(key, frame=3)], frames=frames)
    with pytest.raises(vdg.Error, match="frame"):
        vdg.build(base, tris, [dict(key, frame=2)])  # a static model's keys are at frame 0
    with pytest.raises(ValueError, match="key 'k': frame: expected a frame >= 0"):
        vdg.build(base, tris, [dict(key, frame=-1)], frames=frames)
    with pytest.raises(ValueError, match="fps: expected a number > 0"):
        vdg.build(base, tris, [key], frames=frames, fps=0.0)


def test_key_and_camera_errors() -> None:
    base, _ = tiny_mesh()
    with pytest.raises(ValueError, match="key 'k': give a view or a camera"):
        vdg.Key("k", base)
    with pytest.raises(TypeError, match="camera must be a vdg.Camera"):
        vdg.Key("k", base, camera={"eye": [0, 0, 1]})
    with pytest.raises(vdg.Error):
        vdg.Camera([0, 0, 1], [0, 0, 1])  # the eye is the target
    with pytest.raises(ValueError, match="fov_deg"):
        vdg.Camera([0, 0, 5], [0, 0, 0], fov_deg=180.0)
    camera = vdg.Camera([0, 0, 5], [0, 0, 0])
    key = vdg.Key("k", base, camera=camera)
    assert key.camera is not None and key.camera.fov_deg == 40.0


def test_save_errors_leave_nothing(models: dict[str, vdg.Model], tmp_path: pathlib.Path) -> None:
    head = models["head"]
    with pytest.raises(vdg.Error, match="does not exist"):
        head.save_manifest(tmp_path / "missing" / "head.vdg.json")
    assert not (tmp_path / "missing").exists()
    for folder in ("../out", "/abs", ""):
        with pytest.raises(ValueError, match="mesh_folder"):
            head.save_manifest(tmp_path / "head.vdg.json", mesh_folder=folder)
    with pytest.raises(ValueError, match="expected a manifest file name"):
        head.save_manifest(tmp_path / "head.obj")
    with pytest.raises(vdg.Error, match="skinned offsets"):
        models["walker"].save_manifest(tmp_path / "walker.vdg.json")
    # A file where the mesh folder should be: the step fails, and nothing is written.
    (tmp_path / "keys").write_text("not a folder")
    with pytest.raises(vdg.Error):
        head.save_manifest(tmp_path / "head.vdg.json")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["keys"]


def test_export_errors(models: dict[str, vdg.Model], exported: dict[str, pathlib.Path],
                       tmp_path: pathlib.Path) -> None:
    head = models["head"]
    with pytest.raises(ValueError, match="expected a .glb or .gltf file name"):
        head.export_gltf(tmp_path / "head.obj")
    with pytest.raises(ValueError, match="compress: expected 'none', 'quantize' or 'meshopt', got 'zip'"):
        head.export_gltf(tmp_path / "head.glb", compress="zip")
    with pytest.raises(vdg.Error, match="max-targets"):
        head.export_gltf(tmp_path / "head.glb", max_targets=1)
    with pytest.raises(ValueError, match="max_targets"):
        head.export_gltf(tmp_path / "head.glb", max_targets=-1)
    assert not list(tmp_path.iterdir())
    # A model loaded from a glTF export refuses to be exported over its own file.
    again = vdg.load(exported["head"])
    with pytest.raises(vdg.Error, match="does not write over its input"):
        again.export_gltf(exported["head"])
    assert vdg.load(exported["head"]).weights([0, 0, 1]) == again.weights([0, 0, 1])


def test_no_crash_on_odd_arguments(models: dict[str, vdg.Model]) -> None:
    """Arguments of every odd kind raise one of the three exceptions; none crashes the process."""
    odd = [None, 0, -1, 1.5, float("nan"), "", "x", b"x", [], [[]], [1, 2, 3, 4], np.zeros((0, 3)),
           np.zeros((2, 3)), np.array([1, 2, 3], dtype=np.uint8), object(), {"a": 1}, (1, 2, 3), 10**40]
    calls = [
        lambda m, a: m.weights(a), lambda m, a: m.weights([0, 0, 1], sharpness=a),
        lambda m, a: m.weights([0, 0, 1], frame=a), lambda m, a: m.evaluate(a),
        lambda m, a: m.evaluate([0, 0, 1], frame=a), lambda m, a: m.view_from_eye(a),
        lambda m, a: m.time_coefficients(a, 0.0), lambda m, a: m.time_coefficients(0, a),
        lambda m, a: vdg.build(a, m.triangles, m.keys), lambda m, a: vdg.build(m.base, a, m.keys),
        lambda m, a: vdg.build(m.base, m.triangles, a), lambda m, a: vdg.Key("k", a, view=[0, 0, 1]),
        lambda m, a: vdg.Camera(a, [0, 0, 0]), lambda m, a: vdg.load(a),
    ]
    for model in (models["head"], models["walker"]):
        for call in calls:
            for arg in odd:
                try:
                    call(model, arg)
                except (ValueError, TypeError, vdg.Error):
                    pass


def test_positions_space_is_refused_in_one_line() -> None:
    """Keys at distances (docs/weights.md) weigh eye positions; the module's views are directions."""
    model = vdg.load(EXAMPLES / "spot" / "spot-dolly.vdg.json")
    for call in (lambda: model.weights([0, 0.15, -1]), lambda: model.evaluate([0, 0.15, -1])):
        with pytest.raises(ValueError, match="the 'positions' weight space is not supported by the Python module") as e:
            call()
        assert "\n" not in str(e.value)
    # weights_from_eye weighs the eye itself: exact at the close-up's eye, as vdg weights --eye.
    close = [0.0, 0.34577573612676116, -1.392252658827176]
    w = model.weights_from_eye(close)
    assert w["keys"]["front-close"] == pytest.approx(1.0, abs=1e-6)
    assert sum(w["keys"].values()) + w["base"] == pytest.approx(1.0, abs=1e-5)
