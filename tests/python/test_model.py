"""`import vdg` on its own: the animated model's time coefficients (Rademacher 99, section 4.2),
build() from arrays and its round trips through save_manifest and export_gltf."""
from __future__ import annotations

import pathlib
import threading

import numpy as np
import pytest

import vdg
from conftest import MODELS, random_views

# Coefficients of a cardinal spline are exact at its knots up to double rounding.
COEFF_TOL = 1e-9
WEIGHT_TOL = 1e-6
# Positions at a key's frame and view equal the key mesh to float rounding (animated_model.h),
# relative to the model's size.
KEY_MESH_TOL = 1e-5


@pytest.mark.parametrize("name", ["walker", "walker_world"])
def test_time_coefficients_at_key_frames(name: str, models: dict[str, vdg.Model]) -> None:
    """At key frame f_j of a view, coefficient j is 1 and the others 0; at any frame they sum to 1."""
    model = models[name]
    rng = np.random.default_rng(3)
    views = {}
    for key in model.keys:
        views.setdefault(tuple(np.round(key.view, 9)), []).append(key.frame)
    for index, point in enumerate(model.sphere.points[: model.sphere.key_points]):
        frames = sorted(views[tuple(np.round(point, 9))])
        for j, f in enumerate(frames):
            c = model.time_coefficients(index, f)
            np.testing.assert_allclose(c, np.eye(len(frames))[j], atol=COEFF_TOL)
        for f in rng.uniform(-5, model.frame_count + 5, size=20):
            assert model.time_coefficients(index, f).sum() == pytest.approx(1.0, abs=COEFF_TOL)


@pytest.mark.parametrize("name", ["walker", "walker_world"])
def test_weights_at_fractional_frames(name: str, models: dict[str, vdg.Model]) -> None:
    """The shape-key values at any frame sum with the base to 1, and at a key's frame and view the
    key weighs 1 (section 4.1)."""
    model = models[name]
    rng = np.random.default_rng(5)
    for view, frame in zip(random_views(30, 9), rng.uniform(0, model.frame_count - 1, size=30)):
        w = model.weights(view, frame=frame)
        assert set(w["keys"]) == {k.name for k in model.keys}
        assert sum(w["keys"].values()) + w["base"] == pytest.approx(1.0, abs=WEIGHT_TOL)
        views = model.weights(view)
        assert w["base"] == views["base"]
    for key in model.keys:
        w = model.weights(key.view, frame=key.frame)
        assert w["keys"][key.name] == pytest.approx(1.0, abs=WEIGHT_TOL)


@pytest.mark.parametrize("name", ["walker", "walker_world"])
def test_evaluate_at_key_frame_and_view_is_the_key_mesh(name: str, models: dict[str, vdg.Model]) -> None:
    model = models[name]
    size = float(np.ptp(model.base, axis=0).max())
    for key in model.keys:
        positions, _ = model.evaluate(key.view, frame=key.frame)
        np.testing.assert_allclose(positions, key.positions, atol=KEY_MESH_TOL * size, rtol=0)


def test_weights_from_eye_and_view_from_eye(models: dict[str, vdg.Model]) -> None:
    model = models["spot"]
    eye = model.center + np.array([3.0, 1.0, -2.0])
    view = model.view_from_eye(eye)
    np.testing.assert_allclose(view, [3, 1, -2] / np.linalg.norm([3, 1, -2]), atol=1e-12)
    assert model.weights_from_eye(eye) == model.weights(view)


def test_properties(models: dict[str, vdg.Model]) -> None:
    spot, walker = models["spot"], models["walker"]
    assert not spot.animated and spot.frame_count == 1 and spot.base_frames is None
    assert spot.base.shape == (spot.vertex_count, 3) and spot.base.dtype == np.float32
    assert spot.triangles.dtype == np.int32 and spot.triangles.shape[1] == 3
    assert spot.uncovered in ("base", "cosine", "cosine2") and spot.offsets == "world"
    assert spot.source.endswith("spot.vdg.json") and repr(spot).startswith("<vdg.Model 'spot.vdg.json': ")
    assert len({k.name for k in spot.keys}) == len(spot.keys)
    sphere = spot.sphere
    assert sphere.key_points == len(spot.keys)
    np.testing.assert_allclose(np.linalg.norm(sphere.points, axis=1), 1.0, atol=1e-12)
    for key, point in zip(spot.keys, sphere.points):
        np.testing.assert_allclose(key.view, point, atol=1e-12)
    assert sphere.triangles.max() < len(sphere.points)
    assert walker.animated and walker.offsets == "skinned"
    assert walker.base_frames.shape == (walker.frame_count, walker.vertex_count, 3)
    np.testing.assert_array_equal(walker.base_frames[0], walker.base)


def spot_keys(model: vdg.Model) -> list[object]:
    """Spot's keys, alternately as vdg.Key objects and as dicts (both forms build() takes)."""
    keys: list[object] = []
    for i, key in enumerate(model.keys):
        if i % 2:
            keys.append({"name": key.name, "positions": key.positions, "view": key.view})
        elif key.camera is not None:
            keys.append(vdg.Key(key.name, key.positions, camera=key.camera))
        else:
            keys.append(vdg.Key(key.name, key.positions.astype(np.float64), view=key.view * 3.0))
    return keys


def assert_same_model(a: vdg.Model, b: vdg.Model, frames: list[int | None]) -> None:
    """The same weights and positions, bit for bit, at random views."""
    for view in random_views(20, 11):
        assert a.weights(view) == b.weights(view)
        for frame in frames:
            pa, na = a.evaluate(view, frame=frame)
            pb, nb = b.evaluate(view, frame=frame)
            np.testing.assert_array_equal(pa, pb)
            np.testing.assert_array_equal(na, nb)


def test_build_static_round_trip(models: dict[str, vdg.Model], tmp_path: pathlib.Path) -> None:
    spot = models["spot"]
    built = vdg.build(spot.base, spot.triangles, spot_keys(spot), sharpness=spot.sharpness,
                      uncovered=spot.uncovered, center=spot.center, comment="from Python")
    assert [k.name for k in built.keys] == [k.name for k in spot.keys]
    assert built.comment == "from Python" and not built.animated and built.source == ""
    assert repr(built) == f"<vdg.Model (built): {spot.vertex_count} vertices, {len(spot.keys)} keys, static>"
    for view in random_views(20, 12):
        ours, theirs = built.weights(view), spot.weights(view)
        for name in ours["keys"]:
            assert ours["keys"][name] == pytest.approx(theirs["keys"][name], abs=WEIGHT_TOL)
    built.save_manifest(tmp_path / "built.vdg.json")
    assert (tmp_path / "keys" / "base.obj").is_file()
    loaded = vdg.load(tmp_path / "built.vdg.json")
    assert loaded.comment == "from Python"
    assert_same_model(built, loaded, [None])
    assert not list(tmp_path.glob(".vdg-*")), "the transaction left its journal or temporaries"


def test_smooth_scheme_round_trip(models: dict[str, vdg.Model], tmp_path: pathlib.Path) -> None:
    """build(scheme="smooth") (docs/weights.md): exact at every key, weights summing to 1, the scheme
    kept through save_manifest and export_gltf; an unknown scheme is refused."""
    spot = models["spot"]
    assert spot.scheme == "linear"
    smooth = vdg.build(spot.base, spot.triangles, spot_keys(spot), scheme="smooth")
    assert smooth.scheme == "smooth"
    for key in smooth.keys:
        w = smooth.weights(key.view)
        for name, value in w["keys"].items():
            assert value == pytest.approx(1.0 if name == key.name else 0.0, abs=WEIGHT_TOL)
    for view in random_views(50, 4):
        w = smooth.weights(view)
        assert sum(w["keys"].values()) + w["base"] == pytest.approx(1.0, abs=WEIGHT_TOL)
        assert min(w["keys"].values(), default=0.0) >= 0.0
    smooth.save_manifest(tmp_path / "smooth.vdg.json")
    assert vdg.load(tmp_path / "smooth.vdg.json").scheme == "smooth"
    smooth.export_gltf(tmp_path / "smooth.glb")
    assert vdg.load(tmp_path / "smooth.glb").scheme == "smooth"
    with pytest.raises(ValueError, match="scheme: expected 'linear', 'smooth' or 'rbf'"):
        vdg.build(spot.base, spot.triangles, spot_keys(spot), scheme="cubic")


def test_rbf_scheme(models: dict[str, vdg.Model], tmp_path: pathlib.Path) -> None:
    """build(scheme="rbf") (docs/weights.md): exact at every key, every key weighs a view between
    them, the weights sum to 1 and are never negative, evaluate() blends them, the scheme survives
    save_manifest and the glTF export (extras v4) weighs as the model, and so do its kernel and width."""
    spot = models["spot"]
    rbf = vdg.build(spot.base, spot.triangles, spot_keys(spot), scheme="rbf")
    assert rbf.scheme == "rbf"
    for key in rbf.keys:
        w = rbf.weights(key.view)
        for name, value in w["keys"].items():
            assert value == pytest.approx(1.0 if name == key.name else 0.0, abs=WEIGHT_TOL)
    most = 0
    for view in random_views(50, 5):
        w = rbf.weights(view)
        assert sum(w["keys"].values()) + w["base"] == pytest.approx(1.0, abs=WEIGHT_TOL)
        assert min(w["keys"].values(), default=0.0) >= 0.0
        most = max(most, sum(1 for value in w["keys"].values() if value > 0.0))
    assert most > 3, "the rbf weights reach beyond one triangle's keys"
    front = rbf.keys[0]
    positions, normals = rbf.evaluate(front.view)
    assert positions.shape == normals.shape == (len(spot.base), 3)
    assert abs(positions - front.positions).max() < 1e-4, "a key's own view shows that key"
    rbf.save_manifest(tmp_path / "rbf.vdg.json")
    assert vdg.load(tmp_path / "rbf.vdg.json").scheme == "rbf"
    rbf.export_gltf(tmp_path / "rbf.glb")
    exported = vdg.load(tmp_path / "rbf.glb")
    assert exported.scheme == "rbf"
    for view in random_views(20, 9):
        assert exported.weights(view) == rbf.weights(view)
    # The kernel and width: the defaults, or build's; kept by save_manifest and export_gltf.
    assert (rbf.kernel, rbf.width) == ("gaussian", 60.0)
    assert (spot.kernel, spot.width) == (None, None)
    wendland = vdg.build(spot.base, spot.triangles, spot_keys(spot), scheme="rbf", kernel="wendland", width=50.0)
    assert (wendland.kernel, wendland.width) == ("wendland", 50.0)
    assert any(wendland.weights(v) != rbf.weights(v) for v in random_views(5, 3))
    wendland.save_manifest(tmp_path / "wendland.vdg.json")
    wendland.export_gltf(tmp_path / "wendland.glb")
    for path in ("wendland.vdg.json", "wendland.glb"):
        again = vdg.load(tmp_path / path)
        assert (again.scheme, again.kernel, again.width) == ("rbf", "wendland", 50.0)
        for view in random_views(10, 4):
            assert again.weights(view) == wendland.weights(view)
    with pytest.raises(ValueError, match="kernel, width: settings of the 'rbf' scheme only"):
        vdg.build(spot.base, spot.triangles, spot_keys(spot), scheme="smooth", width=50.0)
    with pytest.raises(ValueError, match="kernel: expected 'gaussian', 'inverse-multiquadric' or 'wendland'"):
        vdg.build(spot.base, spot.triangles, spot_keys(spot), scheme="rbf", kernel="cubic")
    with pytest.raises(ValueError, match=r"width: expected degrees in \(0, 180\]"):
        vdg.build(spot.base, spot.triangles, spot_keys(spot), scheme="rbf", width=0.0)


def test_build_animated_round_trip(models: dict[str, vdg.Model], tmp_path: pathlib.Path) -> None:
    source = models["walker_world"]
    keys = [vdg.Key(k.name, k.positions, view=k.view, frame=k.frame) for k in source.keys]
    frames = source.base_frames
    built = vdg.build(None, source.triangles, keys, frames=frames, loop=source.loop, center=source.center,
                      sharpness=source.sharpness, uncovered=source.uncovered)
    assert built.animated and built.frame_count == source.frame_count
    for view in random_views(10, 13):
        assert built.weights(view) == source.weights(view)
    built.save_manifest(tmp_path / "anim.vdg.json", mesh_folder="meshes/anim")
    assert len(list((tmp_path / "meshes" / "anim").glob("base_*.obj"))) == source.frame_count
    loaded = vdg.load(tmp_path / "anim.vdg.json")
    assert loaded.animated and loaded.loop == source.loop
    assert_same_model(built, loaded, [0, source.frame_count // 2, source.frame_count - 1])


def test_saved_loaded_model_saves_again(models: dict[str, vdg.Model], tmp_path: pathlib.Path) -> None:
    """A shipped model saved by Python loads with the same weights and positions (world offsets)."""
    for name in ("spot", "head", "walker_world"):
        models[name].save_manifest(tmp_path / f"{name}.vdg.json", mesh_folder=name)
        loaded = vdg.load(tmp_path / f"{name}.vdg.json")
        frames = [None] if not loaded.animated else [0, 7]
        for view in random_views(5, 14):
            assert loaded.weights(view) == models[name].weights(view)
            for frame in frames:
                np.testing.assert_array_equal(loaded.evaluate(view, frame=frame)[0],
                                              models[name].evaluate(view, frame=frame)[0])


@pytest.mark.parametrize("name", sorted(MODELS))
def test_export_gltf_loads_back(name: str, models: dict[str, vdg.Model], tmp_path: pathlib.Path) -> None:
    model = models[name]
    out = tmp_path / f"{name}.glb"
    model.export_gltf(out)
    again = vdg.load(out)
    assert [k.name for k in again.keys] == [k.name for k in model.keys]
    frame = 3 if model.animated else None
    size = float(np.ptp(model.base, axis=0).max())
    for view in random_views(10, 15):
        a, b = model.weights(view), again.weights(view)
        assert a.keys() == b.keys() and a["base"] == pytest.approx(b["base"], abs=WEIGHT_TOL)
        np.testing.assert_allclose(model.evaluate(view, frame=frame)[0], again.evaluate(view, frame=frame)[0],
                                   atol=KEY_MESH_TOL * size, rtol=0)


def test_gltf_form_writes_its_buffer(models: dict[str, vdg.Model], tmp_path: pathlib.Path) -> None:
    written = models["head"].export_gltf(tmp_path / "head.gltf", compress="quantize")
    assert written[:2] == [str(tmp_path / "head.gltf"), str(tmp_path / "head.bin")]
    assert all(pathlib.Path(f).is_file() for f in written)
    assert len(vdg.load(tmp_path / "head.gltf").keys) == len(models["head"].keys)


def test_evaluate_releases_the_gil(models: dict[str, vdg.Model]) -> None:
    """Threads evaluating one model at once get what one thread gets."""
    model = models["spot"]
    views = random_views(8, 16)
    expected = [model.evaluate(v)[0] for v in views]
    results: list[list[np.ndarray]] = [[] for _ in range(4)]

    def work(slot: int) -> None:
        for _ in range(5):
            results[slot].append(np.stack([model.evaluate(v)[0] for v in views]))

    threads = [threading.Thread(target=work, args=(i,)) for i in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for slot in results:
        assert len(slot) == 5
        for batch in slot:
            np.testing.assert_array_equal(batch, np.stack(expected))


def test_materials_and_corner_uvs_round_trip(models: dict[str, vdg.Model], tmp_path: pathlib.Path) -> None:
    """Spot's texture, base colour and per-corner uvs survive build -> save_manifest -> load (the OBJ + MTL
    + texture bytes) and build -> export_gltf -> load (the glTF material), as a DCC tool hands them over."""
    spot = models["spot"]
    assert spot.corner_uvs is not None and spot.corner_uvs.shape == (len(spot.triangles), 3, 2)
    assert spot.uvs is None  # Spot's seams give some vertices two (u, v): only corners hold them
    (material,) = spot.materials
    assert material["texture"][:8] == b"\x89PNG\r\n\x1a\n" and material["name"] == "spot"
    built = vdg.build(spot.base, spot.triangles, spot.keys, corner_uvs=spot.corner_uvs,
                      materials=spot.materials, face_materials=spot.face_materials)
    built.save_manifest(tmp_path / "spot.vdg.json")
    saved = vdg.load(tmp_path / "spot.vdg.json")
    np.testing.assert_array_equal(saved.corner_uvs, spot.corner_uvs)
    np.testing.assert_array_equal(saved.face_materials, spot.face_materials)
    assert saved.materials[0]["texture"] == material["texture"]  # the file's own bytes
    assert saved.materials[0]["base_color"] == material["base_color"]
    built.export_gltf(tmp_path / "spot.glb")
    exported = vdg.load(tmp_path / "spot.glb")
    assert exported.materials[0]["texture"][:8] == b"\x89PNG\r\n\x1a\n"
    np.testing.assert_allclose(exported.materials[0]["base_color"], material["base_color"], atol=1e-6)
    np.testing.assert_allclose(exported.corner_uvs, spot.corner_uvs, atol=1e-6, rtol=0)


def test_colour_without_texture_and_faces_without_material(tmp_path: pathlib.Path) -> None:
    """A base colour alone, and faces without a material after faces with one, save and load."""
    base = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], np.float32)
    tris = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]], np.int32)
    keys = [{"name": "k", "positions": base * 1.5, "view": [0, 0, 1]}]
    model = vdg.build(base, tris, keys, materials=[{"name": "red paint", "base_color": (1.0, 0.25, 0.0)}],
                      face_materials=[0, 0, -1, 0])
    model.save_manifest(tmp_path / "m.vdg.json")
    loaded = vdg.load(tmp_path / "m.vdg.json")
    names = [m["name"] for m in loaded.materials]
    assert names[0] == "red_paint" and loaded.materials[0]["base_color"] == (1.0, 0.25, 0.0)
    assert loaded.materials[0]["texture"] is None
    assert [names[i] for i in loaded.face_materials] == ["red_paint", "red_paint", "vdg-plain", "red_paint"]


def test_parts_follow_their_own_views(tmp_path: pathlib.Path) -> None:
    """Per-part key sets (docs/weights.md): the cubist Spot's head keeps its fixed front view while
    the rest follows the camera; away from the head's border each region equals plain Spot at its
    part's view, and weights() lists the parts as `vdg weights --json` does."""
    examples = pathlib.Path(__file__).resolve().parents[2] / "examples" / "spot"
    cubist = vdg.load(str(examples / "spot-cubist.vdg.json"))
    plain = vdg.load(str(examples / "spot.vdg.json"))
    assert cubist.parts == ["head"] and plain.parts == []
    side, front = (1.0, 0.1, 0.0), (0.0, 0.15, -1.0)
    w = cubist.weights(side)
    assert [p["name"] for p in w["parts"]] == ["head", "rest"]
    assert w["parts"][0]["keys"] == pytest.approx({"head-front": 1.0}, abs=WEIGHT_TOL)
    assert w["parts"][1]["keys"] == pytest.approx({"body-right": 1.0}, abs=WEIGHT_TOL)
    positions, _ = cubist.evaluate(side)
    at_side, _ = plain.evaluate(side)
    at_front, _ = plain.evaluate(front)
    base, _ = plain.evaluate((0.0, -1.0, 0.0))  # below the keys: the base
    z = base[:, 2]
    head, body = z < -0.3, z > -0.3 + 0.2  # the head's selection, and beyond its 0.2 border
    np.testing.assert_allclose(positions[head], at_front[head], atol=KEY_MESH_TOL)
    np.testing.assert_allclose(positions[body], at_side[body], atol=KEY_MESH_TOL)
    cubist.save_manifest(str(tmp_path / "copy.vdg.json"))  # parts kept, the same positions
    again = vdg.load(str(tmp_path / "copy.vdg.json"))
    assert again.parts == ["head"]
    np.testing.assert_array_equal(again.evaluate(side)[0], positions)
    with pytest.raises(vdg.Error, match="model parts"):
        cubist.export_gltf(str(tmp_path / "never.glb"))
    assert not (tmp_path / "never.glb").exists()
