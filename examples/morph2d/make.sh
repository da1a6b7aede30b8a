#!/bin/sh
# The 2D morph example (docs/morph.md): a feature-based (Beier-Neely) and a two-pass mesh-warp morph
# between the two faces of this folder, a warp-only sequence, and the inbetweened key drawings.
#
#   examples/morph2d/make.sh [OUT_DIR]       (default out/morph2d; VDG=path/to/vdg to choose the binary)
#
# Writes OUT_DIR/lines/, OUT_DIR/grid/, OUT_DIR/warp/ (frame_0000.png ... frame_0008.png, t = i/8)
# OUT_DIR/drawings/ (13 PNG frames spanning the keys' times) and OUT_DIR/sequences/ (8 frames
# morphing face A swaying into face B bobbing: two animated sequences, drawn first into
# OUT_DIR/seq_a/ and OUT_DIR/seq_b/ by make_faces.py --sequences, with key grids that follow them). With ffmpeg on PATH it also
# writes OUT_DIR/lines.gif and OUT_DIR/grid.gif. face_a.png, face_b.png and drawings.json are made
# by make_faces.py (python3 make_faces.py rewrites them byte for byte).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
out=${1:-out/morph2d}
vdg=${VDG:-vdg}
video_lines="" video_grid=""
if command -v ffmpeg >/dev/null 2>&1; then
  video_lines="--video $out/lines.gif" video_grid="--video $out/grid.gif"
fi
mkdir -p "$out"
# shellcheck disable=SC2086 # the --video options split on purpose
"$vdg" morph "$here/face_a.png" "$here/face_b.png" --lines "$here/lines.json" --count 9 -o "$out/lines" $video_lines
# shellcheck disable=SC2086
"$vdg" morph "$here/face_a.png" "$here/face_b.png" --grid "$here/grid.json" --count 9 -o "$out/grid" $video_grid
"$vdg" morph "$here/face_a.png" "$here/face_b.png" --grid "$here/grid.json" --warp --count 9 -o "$out/warp"
"$vdg" morph --drawings "$here/drawings.json" --count 13 --format png -o "$out/drawings"
python3 "$here/make_faces.py" --sequences "$out"
"$vdg" morph "$out/seq_a" "$out/seq_b" --grid "$out/seq_grid.json" --count 8 -o "$out/sequences"
