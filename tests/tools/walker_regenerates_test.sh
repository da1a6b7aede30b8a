#!/usr/bin/env bash
# examples/walk/make_walker.py regenerates the committed walking character byte for byte:
#   walker_regenerates_test.sh REPO_ROOT WORK_DIR
set -euo pipefail
root=$1
work=$2
rm -rf "$work" && mkdir -p "$work"
python3 "$root/examples/walk/make_walker.py" "$work" >/dev/null
status=0
for f in walker.glb walker.vdg.json walker-world.vdg.json base_f10.obj base_f30.obj \
         keys/front_f10.obj keys/front_f30.obj keys/side_f10.obj keys/side_f30.obj; do
  if ! cmp -s "$work/$f" "$root/examples/walk/$f"; then
    echo "FAIL: examples/walk/$f differs from what make_walker.py writes (rerun it and commit)"
    status=1
  fi
done
# Nothing else is written.
extra=$(cd "$work" && find . -type f | sort | grep -vxF -e ./walker.glb -e ./walker.vdg.json \
  -e ./walker-world.vdg.json -e ./base_f10.obj -e ./base_f30.obj -e ./keys/front_f10.obj \
  -e ./keys/front_f30.obj -e ./keys/side_f10.obj -e ./keys/side_f30.obj || true)
if [ -n "$extra" ]; then
  echo "FAIL: make_walker.py wrote files the test does not know: $extra"
  status=1
fi
exit $status
