"""Shared fixtures of the `import vdg` tests: the module, the vdg tool, the shipped models."""
from __future__ import annotations

import json
import os
import pathlib
import subprocess
from typing import Any

import numpy as np
import pytest

import vdg

SOURCE_DIR = pathlib.Path(__file__).resolve().parents[2]
EXAMPLES = SOURCE_DIR / "examples"

# The shipped models every parity test runs on: static, animated skinned, animated with
# world offsets, and the paper's figure 13 head.
MODELS = {
    "spot": EXAMPLES / "spot" / "spot.vdg.json",
    "walker": EXAMPLES / "walk" / "walker.vdg.json",
    "walker_world": EXAMPLES / "walk" / "walker-world.vdg.json",
    "head": EXAMPLES / "figure13" / "head" / "head.vdg.json",
}


def vdg_tool() -> str:
    """The vdg command-line tool named by $VDG_TOOL (ctest sets it); skips the test without it."""
    tool = os.environ.get("VDG_TOOL", "")
    if not tool or not os.access(tool, os.X_OK):
        pytest.skip("VDG_TOOL does not name the vdg tool")
    return tool


def run_vdg(*args: str) -> str:
    """Runs the vdg tool, returning its standard output; fails the test on a non-zero exit."""
    done = subprocess.run([vdg_tool(), *args], capture_output=True, text=True, check=False)
    assert done.returncode == 0, f"vdg {' '.join(args)}: {done.stderr}"
    return done.stdout


def random_views(count: int, seed: int) -> np.ndarray:
    """`count` unit directions spread over the sphere (a fixed seed: reproducible failures)."""
    rng = np.random.default_rng(seed)
    v = rng.normal(size=(count, 3))
    return v / np.linalg.norm(v, axis=1, keepdims=True)


def cli_weights(model: pathlib.Path | str, views: np.ndarray, work: pathlib.Path) -> list[dict[str, Any]]:
    """`vdg weights MODEL --views FILE`: one JSON object per view, in order."""
    views_file = work / "views.json"
    views_file.write_text(json.dumps(views.tolist()))
    return json.loads(run_vdg("weights", str(model), "--views", str(views_file)))


@pytest.fixture(scope="session")
def exported(tmp_path_factory: pytest.TempPathFactory) -> dict[str, pathlib.Path]:
    """Each shipped model exported by `vdg export` as .glb (once per session)."""
    out = tmp_path_factory.mktemp("exported")
    files = {}
    for name, path in MODELS.items():
        files[name] = out / f"{name}.glb"
        run_vdg("export", str(path), "-o", str(files[name]), "-q")
    return files


@pytest.fixture(scope="session")
def models() -> dict[str, vdg.Model]:
    """The shipped models, loaded once."""
    return {name: vdg.load(path) for name, path in MODELS.items()}
