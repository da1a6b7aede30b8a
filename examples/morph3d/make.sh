#!/usr/bin/env bash
# The distance-field morph of a sphere into a torus (Parent 4.10, "Distance Fields"; docs/morph3d.md):
#   examples/morph3d/make.sh VDG_BINARY OUT_DIR [--figures]
# writes OUT_DIR/frames/frame_0000.obj ... frame_0008.obj (t = 0, 1/8, ..., 1) with vdg morph3d,
# and renders each with vdg render through the sequence's own camera (OUT_DIR/frames/camera.json,
# the same for every frame) to OUT_DIR/png/frame_0000.png ... With --figures it also copies frames
# 0, 4 and 8 to docs/images/morph3d_t0.png, morph3d_t05.png and morph3d_t1.png.
# The meshes sphere.obj and torus.obj are made by make_shapes.py (already in this folder).
set -euo pipefail
if [ $# -lt 2 ] || [ $# -gt 3 ]; then
  echo "usage: examples/morph3d/make.sh VDG_BINARY OUT_DIR [--figures]" >&2
  exit 2
fi
vdg=$1
out=$2
figures=${3:-}
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
frames=9
mkdir -p "$out/png"

"$vdg" morph3d "$here/sphere.obj" "$here/torus.obj" --count "$frames" -o "$out/frames"
# Every frame has its own connectivity (the hole opens on the way), so each is rendered as a mesh
# of its own, all through the one camera that frames every frame.
for ((i = 0; i < frames; i++)); do
  name=$(printf 'frame_%04d' "$i")
  "$vdg" render "$out/frames/$name.obj" --camera "$out/frames/camera.json" --size 320x320 --quiet -o "$out/render_$name"
  mv "$out/render_$name/frame_0000.png" "$out/png/$name.png"
  rmdir "$out/render_$name"
done

if [ "$figures" = "--figures" ]; then
  cp "$out/png/frame_0000.png" "$root/docs/images/morph3d_t0.png"
  cp "$out/png/frame_0004.png" "$root/docs/images/morph3d_t05.png"
  cp "$out/png/frame_0008.png" "$root/docs/images/morph3d_t1.png"
fi
echo "morph3d example: wrote $out/frames/ (meshes) and $out/png/ (renders)"
