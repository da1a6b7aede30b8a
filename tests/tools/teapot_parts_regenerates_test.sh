#!/usr/bin/env bash
# examples/meshes/make_teapot_parts.py regenerates the committed teapot-parts.obj/.mtl byte for byte:
#   teapot_parts_regenerates_test.sh REPO_ROOT WORK_DIR
set -euo pipefail
root=$1
work=$2
rm -rf "$work" && mkdir -p "$work"
python3 "$root/examples/meshes/make_teapot_parts.py" "$work" >/dev/null
status=0
for f in teapot-parts.obj teapot-parts.mtl; do
  if ! cmp -s "$work/$f" "$root/examples/meshes/$f"; then
    echo "FAIL: examples/meshes/$f differs from what make_teapot_parts.py writes (rerun it and commit)"
    status=1
  fi
done
# Every part is found (the script prints its face counts; none may be zero).
counts=$(python3 "$root/examples/meshes/make_teapot_parts.py" "$work")
echo "$counts"
if echo "$counts" | grep -qE '(body|lid|knob|handle|spout) 0\b'; then
  echo "FAIL: a part of the teapot has no faces"
  status=1
fi
exit $status
