#!/usr/bin/env bash
# run_blender_check.sh VDG SOURCE_DIR WORK_DIR BLENDER
# Exports examples/spot as .glb and .gltf (with its texture beside it) and has Blender import each
# (check_textured_import.py). Exit 77 (skip) when Blender is missing, unless VDG_REQUIRE_BLENDER=1.
set -euo pipefail
vdg=$1 src=$2 work=$3 blender=${4:-}
if [[ -z "$blender" || ! -x "$blender" ]]; then
  if [[ "${VDG_REQUIRE_BLENDER:-0}" == 1 ]]; then
    echo "blender is not installed, and VDG_REQUIRE_BLENDER=1 (scripts/install-deps installs it)" >&2
    exit 1
  fi
  echo "blender is not installed: skipped" >&2
  exit 77
fi
rm -rf "$work"
mkdir -p "$work"
"$vdg" export "$src/examples/spot/spot.vdg.json" -o "$work/spot.glb" -q
"$vdg" export "$src/examples/spot/spot.vdg.json" -o "$work/spot.gltf" -q
# Blender embeds Debian's Python: a pyenv on PATH or in the environment makes its glTF importer miss
# Debian's numpy (/work/shared/CHECKED.md), so both are removed.
clean_path=$(printf '%s' "$PATH" | tr ':' '\n' | grep -v pyenv | paste -sd: -)
for file in "$work/spot.glb" "$work/spot.gltf"; do
  env -u PYTHONHOME $(env | sed -n 's/^\(PYENV[A-Za-z_]*\)=.*/-u \1/p') PATH="$clean_path" \
    PYTHONPATH=/usr/lib/python3/dist-packages \
    "$blender" -b --factory-startup --python-exit-code 1 \
    --python "$src/tests/blender/check_textured_import.py" -- "$file" "$src/examples/spot" >"$work/blender.log" 2>&1 ||
    { cat "$work/blender.log" >&2; exit 1; }
  grep '^check:' "$work/blender.log"
done
