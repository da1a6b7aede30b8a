#!/usr/bin/env bash
# run_addon_check.sh VDG SOURCE_DIR WORK_DIR BLENDER ADDON_ZIP CASE
# Runs check_addon.py CASE in Blender 3.4 with the add-on installed from ADDON_ZIP. Blender's user
# folders (HOME, BLENDER_USER_*) live in WORK_DIR, so nothing lands in ~/.config. Exit 77 (skip) when
# Blender is missing, unless VDG_REQUIRE_BLENDER=1.
set -euo pipefail
vdg=$1 src=$2 work=$3 blender=${4:-} zip=$5 case=$6
if [[ -z "$blender" || ! -x "$blender" ]]; then
  if [[ "${VDG_REQUIRE_BLENDER:-0}" == 1 ]]; then
    echo "blender is not installed, and VDG_REQUIRE_BLENDER=1 (scripts/install-deps installs it)" >&2
    exit 1
  fi
  echo "blender is not installed: skipped" >&2
  exit 77
fi
if [[ ! -f "$zip" ]]; then
  echo "$zip is missing: build the vdg_blender_addon target" >&2
  exit 1
fi
rm -rf "$work"
mkdir -p "$work/home" "$work/scripts" "$work/config" "$work/out"
# Blender embeds Debian's Python: a pyenv on PATH or in the environment makes it miss Debian's numpy
# (/work/shared/CHECKED.md), so both are removed; PYTHONPATH keeps only Debian's dist-packages, so the
# add-on's `import vdg` is the zip's copy.
clean_path=$(printf '%s' "$PATH" | tr ':' '\n' | grep -v pyenv | paste -sd: -)
status=0
env -u PYTHONHOME $(env | sed -n 's/^\(PYENV[A-Za-z_]*\)=.*/-u \1/p') PATH="$clean_path" \
  PYTHONPATH=/usr/lib/python3/dist-packages HOME="$work/home" \
  BLENDER_USER_SCRIPTS="$work/scripts" BLENDER_USER_CONFIG="$work/config" \
  "$blender" -b --factory-startup --python-exit-code 1 \
  --python "$src/tests/blender/check_addon.py" -- "$case" "$vdg" "$src" "$zip" "$work/out" \
  >"$work/blender.log" 2>&1 || status=$?
if [[ $status != 0 ]] || ! grep -q '^check: done' "$work/blender.log"; then
  cat "$work/blender.log" >&2
  exit 1
fi
grep '^check:' "$work/blender.log"
