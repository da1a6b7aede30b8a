#!/usr/bin/env bash
# The blobby animation of docs/implicit.md, reproducible by one command:
#   examples/implicit/make.sh [VDG_BINARY [OUT_DIR]]     (defaults: build/ci/bin/vdg, out/implicit)
# writes OUT_DIR/obj/frame_0000.obj ... frame_0047.obj (with camera.json and sequence.json, from
# `vdg implicit --frames`) and renders each frame with `vdg render` through the sequence's one
# camera into OUT_DIR/png/frame_0000.png ... (the frames change topology as the blobs fuse and
# part, so each is rendered as its own mesh). With --figures as a third argument it also copies
# frames 0, 20 and 40 to docs/images/implicit_frame_NN.png.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
vdg=${1:-$root/build/ci/bin/vdg}
out=${2:-out/implicit}
figures=${3:-}

"$vdg" implicit "$here/blobs.json" --frames 0-47 -o "$out/obj"
mkdir -p "$out/png"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for obj in "$out"/obj/frame_*.obj; do
  name=$(basename "$obj" .obj)
  "$vdg" render "$obj" --camera "$out/obj/camera.json" --size 400x400 --color 0.95,0.75,0.55 -o "$tmp/$name" --quiet
  mv "$tmp/$name/frame_0000.png" "$out/png/$name.png"
done
if [ "$figures" = "--figures" ]; then
  for f in 0000 0020 0040; do cp "$out/png/frame_$f.png" "$root/docs/images/implicit_frame_${f:2}.png"; done
fi
echo "make.sh: wrote $out/obj (48 OBJ frames) and $out/png (48 PNG frames)"
