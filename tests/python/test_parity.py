"""`import vdg` against the vdg tool at random views: `vdg weights --views` (batch JSON) and
`vdg eval`, on every shipped model and on its glTF export."""
from __future__ import annotations

import json
import pathlib
from typing import Any

import numpy as np
import pytest

import vdg
from conftest import MODELS, cli_weights, random_views, run_vdg

# The CLI prints weights with the 7 significant digits a float holds (cmd_weights.cpp).
WEIGHT_TOL = 1e-6
# `vdg eval` writes positions in the shortest form that round-trips a float: equal to float rounding.
POSITION_TOL = 1e-5
# `vdg eval` writes no normals: the reference is recomputed here in float64 from its positions,
# while vdg sums float32 cross products; on the walkers' small triangles the two differ by up to
# about 1.1e-5 (measured), so the normals get a tolerance of 1e-4 and a unit-length check of 1e-5.
NORMAL_TOL = 1e-4
UNIT_TOL = 1e-5
VIEW_COUNT = 50
EVAL_VIEW_COUNT = 50


def check_static_weights(ours: dict[str, Any], theirs: dict[str, Any]) -> None:
    """Every key the CLI lists (weight > 0) has its weight here; every other key weighs 0."""
    assert set(theirs["keys"]) <= set(ours["keys"])
    for name, w in ours["keys"].items():
        assert w == pytest.approx(theirs["keys"].get(name, 0.0), abs=WEIGHT_TOL), name
    assert ours["base"] == pytest.approx(theirs["base"], abs=WEIGHT_TOL)


def check_animated_weights(ours: dict[str, Any], theirs: dict[str, Any]) -> None:
    """The key views with weight > 0, in the CLI's order, with their keys, frames and weight."""
    assert len(ours["views"]) == len(theirs["views"])
    for a, b in zip(ours["views"], theirs["views"]):
        assert a["keys"] == b["keys"] and a["frames"] == b["frames"]
        np.testing.assert_allclose(a["view"], b["view"], atol=WEIGHT_TOL)
        assert a["weight"] == pytest.approx(b["weight"], abs=WEIGHT_TOL)
    assert ours["base"] == pytest.approx(theirs["base"], abs=WEIGHT_TOL)


def check_weights(model_path: pathlib.Path | str, work: pathlib.Path, seed: int) -> None:
    model = vdg.load(model_path)
    views = random_views(VIEW_COUNT, seed)
    theirs = cli_weights(model_path, views, work)
    assert len(theirs) == VIEW_COUNT
    for view, expected in zip(views, theirs):
        ours = model.weights(view)
        if model.animated:
            check_animated_weights(ours, expected)
        else:
            check_static_weights(ours, expected)
            assert sum(ours["keys"].values()) + ours["base"] == pytest.approx(1.0, abs=WEIGHT_TOL)


@pytest.mark.parametrize("name", sorted(MODELS))
def test_weights_match_cli(name: str, tmp_path: pathlib.Path) -> None:
    check_weights(MODELS[name], tmp_path, seed=len(name))


@pytest.mark.parametrize("name", sorted(MODELS))
def test_weights_of_export_match_cli(name: str, exported: dict[str, pathlib.Path], tmp_path: pathlib.Path) -> None:
    check_weights(exported[name], tmp_path, seed=100 + len(name))


def read_obj_positions(path: pathlib.Path) -> np.ndarray:
    """The `v` lines of an OBJ file vdg wrote, (V, 3) float64."""
    rows = [line.split()[1:4] for line in path.read_text().splitlines() if line.startswith("v ")]
    return np.array(rows, dtype=np.float64)


def area_weighted_normals(positions: np.ndarray, triangles: np.ndarray) -> np.ndarray:
    """Sum of each vertex's triangles' cross products, normalised (vdg/geom/tri_mesh.h)."""
    p = positions[triangles]
    cross = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    sums = np.zeros_like(positions)
    for corner in range(3):
        np.add.at(sums, triangles[:, corner], cross)
    return sums / np.maximum(np.linalg.norm(sums, axis=1, keepdims=True), 1e-300)


def unsplit_vertices(positions: np.ndarray) -> np.ndarray:
    """Vertices no other vertex shares a position with (not on a uv seam: vdg welds seams, so a
    welded vertex's normal sums its copies' triangles)."""
    _, inverse, counts = np.unique(positions, axis=0, return_inverse=True, return_counts=True)
    return counts[inverse.ravel()] == 1


@pytest.mark.parametrize("name", sorted(MODELS))
def test_evaluate_matches_cli_eval(name: str, models: dict[str, vdg.Model], tmp_path: pathlib.Path) -> None:
    model = models[name]
    views = random_views(EVAL_VIEW_COUNT, seed=7 + len(name))
    rng = np.random.default_rng(len(name))
    single = unsplit_vertices(model.base)
    for i, view in enumerate(views):
        out = tmp_path / f"eval{i}.obj"
        args = ["eval", str(MODELS[name]), "--view", ",".join(repr(float(x)) for x in view), "-o", str(out), "-q"]
        frame = None
        if model.animated:
            frame = int(rng.integers(model.frame_count))
            args += ["--frame", str(frame)]
        run_vdg(*args)
        positions, normals = model.evaluate(view, frame=frame)
        expected = read_obj_positions(out)
        np.testing.assert_allclose(positions, expected, atol=POSITION_TOL, rtol=0)
        # The OBJ holds no normals: recompute them from its positions where no seam is welded.
        reference = area_weighted_normals(expected, model.triangles)
        np.testing.assert_allclose(normals[single], reference[single], atol=NORMAL_TOL, rtol=0)
        np.testing.assert_allclose(np.linalg.norm(normals[single], axis=1), 1.0, atol=UNIT_TOL)


def test_export_gltf_is_vdg_export(models: dict[str, vdg.Model], exported: dict[str, pathlib.Path],
                                   tmp_path: pathlib.Path) -> None:
    """export_gltf writes the very bytes `vdg export` writes."""
    for name in ("spot", "walker"):
        out = tmp_path / f"{name}.glb"
        assert models[name].export_gltf(out) == [str(out)]
        assert out.read_bytes() == exported[name].read_bytes(), name


def test_version_is_the_tool_s() -> None:
    assert run_vdg("--version").split()[-1] == vdg.__version__


@pytest.mark.parametrize("name", ["spot", "walker"])
def test_weights_from_eye_match_cli(name: str, models: dict[str, vdg.Model], tmp_path: pathlib.Path) -> None:
    """weights_from_eye(eye) against the batch's {"eye": [x, y, z]} items (`vdg weights --eye`)."""
    model = models[name]
    rng = np.random.default_rng(21)
    eyes = model.center + random_views(VIEW_COUNT, 22) * rng.uniform(0.5, 20.0, size=(VIEW_COUNT, 1))
    views_file = tmp_path / "eyes.json"
    views_file.write_text(json.dumps([{"eye": e.tolist()} for e in eyes]))
    theirs = json.loads(run_vdg("weights", str(MODELS[name]), "--views", str(views_file)))
    for eye, expected in zip(eyes, theirs):
        ours = model.weights_from_eye(eye)
        if model.animated:
            check_animated_weights(ours, expected)
        else:
            check_static_weights(ours, expected)
