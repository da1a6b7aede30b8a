#!/usr/bin/env bash
# examples/figure13/make_head.py regenerates the committed head model byte for byte, and every key
# moves vertices of the base (a key equal to its base would show nothing):
#   head_regenerates_test.sh REPO_ROOT WORK_DIR
set -euo pipefail
root=$1
work=$2
rm -rf "$work" && mkdir -p "$work"
python3 "$root/examples/figure13/make_head.py" "$work"
status=0
for f in head.vdg.json base.obj keys/front.obj keys/left.obj keys/right.obj keys/top.obj; do
  if ! cmp -s "$work/head/$f" "$root/examples/figure13/head/$f"; then
    echo "FAIL: examples/figure13/head/$f differs from what make_head.py writes (rerun it and commit)"
    status=1
  fi
  if [[ $f == keys/* ]] && cmp -s <(grep '^v ' "$work/head/$f") <(grep '^v ' "$work/head/base.obj"); then
    echo "FAIL: $f moves no vertex of the base"
    status=1
  fi
done
exit $status
