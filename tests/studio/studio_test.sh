#!/usr/bin/env bash
# vdg studio under a virtual X server (Xvfb): replayed input, screenshots, start-up errors,
# crash recovery. Usage: studio_test.sh VDG SOURCE_DIR
#   (a) a replayed drag gives the key mesh `vdg deform` gives for the same DragOp (1e-5);
#   (b) a screenshot shows the drawing (known colours) and the model, and matches a golden PNG
#       (VDG_UPDATE_GOLDEN=1 rewrites tests/studio/golden/*.png);
#   (c) a missing model, a corrupt model, a corrupt drawing, a save into a read-only folder: a
#       message on stderr, exit status 1, no file changed;
#   (d) a crash (VDG_STUDIO_ABORT_AT_FRAME) after a stroke, then --recover and Ctrl+S: the same key
#       as without the crash;
#   (g) a key on the animated walker at frame 20 (timeline keys, a drag, Ctrl+S): the manifest's
#       (20, view) key, equal to `vdg deform --frame 20` with the same op and to `vdg eval` there.
#   (h) feature lines drawn in the window and applied: the key vdg deform makes from the logged op.
# Without Xvfb the test is skipped (exit 77), unless VDG_REQUIRE_XVFB=1.
set -u
VDG=$(realpath "$1")
SRC=$(realpath "$2")
HERE="$SRC/tests/studio"
TOOL="python3 $HERE/studio_tool.py"
if ! command -v Xvfb >/dev/null 2>&1; then
  if [ "${VDG_REQUIRE_XVFB:-0}" = 1 ]; then
    echo "studio_test: Xvfb is missing and VDG_REQUIRE_XVFB=1" >&2
    exit 1
  fi
  echo "studio_test: SKIPPED: Xvfb is missing (apt-get install xvfb)"
  exit 77
fi
# Under AddressSanitizer, leak checking is off for the studio process only: Mesa's X11 GL driver,
# loaded with dlopen by GLFW and unloaded at exit, leaves allocations LeakSanitizer cannot even
# attribute ("<unknown module>"); every other ASan and UBSan check stays on.
export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0"
TMP=$(mktemp -d)
# One X server for the whole test, on a free display it reports once it is ready (-displayfd).
# (xvfb-run around every command failed its own clean-up now and then under load: exit 5.)
Xvfb -displayfd 3 -screen 0 1280x800x24 -nolisten tcp 3>"$TMP/display" 2>"$TMP/xvfb.err" &
XVFB_PID=$!
trap 'kill $XVFB_PID 2>/dev/null; chmod -R u+w "$TMP" 2>/dev/null; rm -rf "$TMP"' EXIT
for _ in $(seq 100); do [ -s "$TMP/display" ] && break; sleep 0.1; done
if ! [ -s "$TMP/display" ]; then
  echo "studio_test: Xvfb did not start: $(cat "$TMP/xvfb.err")" >&2
  exit 1
fi
export DISPLAY=":$(head -1 "$TMP/display")"
FAILED=0
fail() { echo "FAIL: $*" >&2; FAILED=1; }
pass() { echo "ok: $*"; }
studio() { "$VDG" studio "$@"; }
building() { mkdir -p "$1" && cp "$SRC"/examples/building/{building.vdg.json,base.obj,front.obj} "$1"/; }
snapshot() { (cd "$1" && find . -type f -print0 | sort -z | xargs -0 sha1sum); }

# The window is 960x600; the tool panel takes the left 300 pixels, so the viewport (no drawing)
# is 660x600 image pixels at x >= 300 and the model, framed, sits at its centre (630, 300).
W=960 H=600 IW=660 IH=600 CX=630 CY=300 DX=40 DY=-25
# An orbit first (the example's key 'front' already has the front view), then a drag in Deform.
ORBIT=("1:mouse_down:$CX:$CY" "2:mouse_move:$((CX - 30)):$CY" "3:mouse_move:$((CX - 50)):$((CY + 10))" "4:mouse_up:$((CX - 50)):$((CY + 10))")
DRAG=("${ORBIT[@]}" "5:key_down:2" "6:key_up:2" "7:mouse_move:$CX:$CY" "8:mouse_down:$CX:$CY" "9:mouse_move:$((CX + 10)):$((CY - 6))"
  "10:mouse_move:$((CX + 25)):$((CY - 15))" "11:mouse_move:$((CX + DX)):$((CY + DY))" "13:mouse_up:$((CX + DX)):$((CY + DY))")
SAVE=("15:key_down:S:ctrl" "16:key_up:S:ctrl")

# ---- (a) replayed drag == vdg deform --------------------------------------------------------
building "$TMP/a"
$TOOL events "$TMP/drag_save.json" $W $H "${DRAG[@]}" "${SAVE[@]}"
if studio "$TMP/a/building.vdg.json" --replay "$TMP/drag_save.json" 2>"$TMP/a.err"; then
  if $TOOL logcheck "$TMP/a/building.vdg.json" key1 $DX $DY $IW $IH; then
    building "$TMP/a_deform"
    $TOOL ops "$TMP/a/building.vdg.json" key1 "$TMP/a_ops.json" &&
      "$VDG" deform "$TMP/a_deform/building.vdg.json" --key key1 --ops "$TMP/a_ops.json" -q >/dev/null &&
      ! $TOOL objclose "$TMP/a/key1.obj" "$TMP/a/base.obj" 1e-4 >/dev/null 2>&1 &&
      $TOOL objclose "$TMP/a/key1.obj" "$TMP/a_deform/key1.obj" 1e-5 &&
      pass "(a) replayed drag gives vdg deform's key mesh" || fail "(a) studio key differs from vdg deform's"
  else
    fail "(a) the saved edit log is not the replayed drag"
  fi
else
  fail "(a) vdg studio --replay failed: $(cat "$TMP/a.err")"
fi

# ---- (b) screenshots ----------------------------------------------------------------------------
# 640x400 window: viewport 340x400 at x = 300; a 200x150 drawing (4:3) letterboxed to 340x255 at
# y = 72. Its corners show the drawing at opacity 0.5 over the paper (0.97, 0.97, 0.95).
$TOOL drawing "$TMP/drawing.png" 200 150
building "$TMP/b"
if studio "$TMP/b/building.vdg.json" --drawing "$TMP/drawing.png" --size 640x400 --count 3 \
  --screenshot "$TMP/b.png" 2>"$TMP/b.err"; then
  $TOOL pixel "$TMP/b.png" 306 80 234 144 141 8 && pass "(b) red half of the drawing at opacity 0.5" ||
    fail "(b) drawing colour (red half)"
  $TOOL pixel "$TMP/b.png" 634 320 144 154 231 8 && pass "(b) blue half of the drawing at opacity 0.5" ||
    fail "(b) drawing colour (blue half)"
  $TOOL notpixel "$TMP/b.png" 470 200 234 144 141 30 && pass "(b) the model covers the drawing's centre" ||
    fail "(b) no model at the viewport's centre"
  if [ "${VDG_UPDATE_GOLDEN:-0}" = 1 ]; then
    cp "$TMP/b.png" "$HERE/golden/studio_drawing.png" && echo "updated $HERE/golden/studio_drawing.png"
  fi
  $TOOL compare "$TMP/b.png" "$HERE/golden/studio_drawing.png" 24 0.02 && pass "(b) screenshot matches the golden" ||
    fail "(b) screenshot differs from golden/studio_drawing.png (see $TMP/b.png)"
else
  fail "(b) vdg studio --screenshot failed: $(cat "$TMP/b.err")"
fi

# ---- (c) errors at start-up and when saving ------------------------------------------------------
expect_error() {  # NAME EXPECTED_TEXT -- ARGS...
  local name=$1 text=$2
  shift 3
  studio "$@" --count 2 >/dev/null 2>"$TMP/c.err"
  local rc=$?
  if [ $rc -eq 1 ] && grep -q -- "$text" "$TMP/c.err"; then pass "(c) $name: exit 1, '$(head -c 150 "$TMP/c.err")'"
  else fail "(c) $name: exit $rc, stderr '$(cat "$TMP/c.err")'"; fi
}
mkdir -p "$TMP/c"
printf 'v 0 0 0\nv 1 0\nf 1 2 7\n' >"$TMP/c/bad.obj"
printf 'not a png' >"$TMP/c/bad.png"
cp "$SRC/examples/building/base.obj" "$TMP/c/good.obj"
before=$(snapshot "$TMP/c")
expect_error "missing model" "missing.obj" -- "$TMP/c/missing.obj"
expect_error "corrupt model" "bad.obj" -- "$TMP/c/bad.obj"
expect_error "corrupt drawing" "bad.png" -- "$TMP/c/good.obj" --drawing "$TMP/c/bad.png"
[ "$(snapshot "$TMP/c")" = "$before" ] && [ ! -e "$TMP/c/.vdg-studio" ] && pass "(c) no file changed" ||
  fail "(c) files changed: $(ls -la "$TMP/c")"

# A read-only folder: root ignores permissions, so run as nobody when we are root.
building "$TMP/ro"
chmod 755 "$TMP"
AS=()
if [ "$(id -u)" = 0 ]; then
  if command -v setpriv >/dev/null 2>&1 && setpriv --reuid=65534 --regid=65534 --clear-groups true 2>/dev/null; then
    AS=(setpriv --reuid=65534 --regid=65534 --clear-groups)
  else
    AS=(skip)
  fi
fi
if [ "${AS[0]:-}" = skip ]; then
  echo "(c) read-only folder: SKIPPED (running as root without setpriv)"
else
  chmod -R a-w "$TMP/ro"
  chmod a+r "$TMP/drag_save.json"
  before=$(snapshot "$TMP/ro")
  "${AS[@]}" "$VDG" studio "$TMP/ro/building.vdg.json" \
    --replay "$TMP/drag_save.json" >/dev/null 2>"$TMP/ro.err"
  rc=$?
  if [ $rc -eq 1 ] && [ -s "$TMP/ro.err" ] && [ "$(snapshot "$TMP/ro")" = "$before" ]; then
    pass "(c) read-only folder: exit 1, '$(head -c 200 "$TMP/ro.err")', nothing changed"
  else
    fail "(c) read-only folder: exit $rc, stderr '$(cat "$TMP/ro.err")'"
  fi
  chmod -R u+w "$TMP/ro"
fi

# ---- (d) crash recovery ------------------------------------------------------------------------------
building "$TMP/d"
$TOOL events "$TMP/drag.json" $W $H "${DRAG[@]}" "24:mouse_move:10:10"
VDG_STUDIO_ABORT_AT_FRAME=16 studio "$TMP/d/building.vdg.json" --replay "$TMP/drag.json" >/dev/null 2>&1
rc=$?
if [ $rc -eq 0 ] || [ $rc -eq 1 ]; then fail "(d) the session did not abort (exit $rc)"; fi
if [ -e "$TMP/d/key1.obj" ]; then fail "(d) the key was saved before the crash"; fi
if ls "$TMP"/d/.vdg-studio/*.recovery.json >/dev/null 2>&1; then
  pass "(d) the aborted session left its recovery file"
else
  fail "(d) no recovery file after the crash"
fi
$TOOL events "$TMP/save.json" $W $H "3:key_down:S:ctrl" "4:key_up:S:ctrl"
if studio "$TMP/d/building.vdg.json" --recover --replay "$TMP/save.json" 2>"$TMP/d.err"; then
  $TOOL objclose "$TMP/d/key1.obj" "$TMP/a/key1.obj" 0 && pass "(d) recovered and saved: the key of the session without the crash" ||
    fail "(d) recovered key differs"
else
  fail "(d) vdg studio --recover failed: $(cat "$TMP/d.err")"
fi

# ---- (e) a real textured model (Spot: materials, a texture, five keys) opens and edits -----------------
mkdir -p "$TMP/e" && cp -r "$SRC"/examples/spot "$TMP/e/"
if studio "$TMP/e/spot/spot.vdg.json" --replay "$TMP/drag_save.json" 2>"$TMP/e.err" && [ -s "$TMP/e/spot/key1.obj" ]; then
  ! $TOOL objclose "$TMP/e/spot/key1.obj" "$TMP/e/spot/spot.obj" 1e-4 >/dev/null 2>&1 &&
    pass "(e) Spot opens, and a replayed drag saves a new key" || fail "(e) Spot's new key did not move"
else
  fail "(e) vdg studio on Spot failed: $(cat "$TMP/e.err")"
fi

# ---- (f) an animated model (the walker) opens with the Preview and its timeline; orbiting saves nothing --
mkdir -p "$TMP/f" && cp -r "$SRC"/examples/walk "$TMP/f/"
$TOOL events "$TMP/preview.json" $W $H "1:key_down:P" "2:key_up:P" "3:mouse_down:$CX:$CY" "4:mouse_move:$((CX + 30)):$CY" \
  "5:mouse_up:$((CX + 30)):$CY" "6:key_down:S:ctrl" "7:key_up:S:ctrl"
before=$(snapshot "$TMP/f")
if studio "$TMP/f/walk/walker.vdg.json" --replay "$TMP/preview.json" --screenshot "$TMP/f.png" 2>"$TMP/f.err" &&
  [ -s "$TMP/f.png" ] && [ "$before" = "$(snapshot "$TMP/f")" ]; then
  pass "(f) the walker opens with its timeline; an orbit and Ctrl+S (no key) change no file"
else
  fail "(f) animated model: $(cat "$TMP/f.err")"
fi

# ---- (g) a key on the walker at a frame: Right x 20 on the timeline, Deform, a drag, Ctrl+S ----------
mkdir -p "$TMP/g" "$TMP/g_deform" && cp -r "$SRC"/examples/walk "$TMP/g/" && cp -r "$SRC"/examples/walk "$TMP/g_deform/"
G=()
n=1
for _ in $(seq 20); do G+=("$n:key_down:Right" "$((n + 1)):key_up:Right"); n=$((n + 2)); done
G+=("$n:key_down:2" "$((n + 1)):key_up:2" "$((n + 2)):mouse_move:$CX:$CY" "$((n + 3)):mouse_down:$CX:$CY"
  "$((n + 4)):mouse_move:$((CX + 10)):$((CY - 6))" "$((n + 5)):mouse_move:$((CX + DX)):$((CY + DY))"
  "$((n + 7)):mouse_up:$((CX + DX)):$((CY + DY))" "$((n + 9)):key_down:S:ctrl" "$((n + 10)):key_up:S:ctrl")
$TOOL events "$TMP/walker_key.json" $W $H "${G[@]}"
WG="$TMP/g/walk/walker.vdg.json"
if studio "$WG" --replay "$TMP/walker_key.json" 2>"$TMP/g.err"; then
  if [ "$($TOOL keyframe "$WG" key1)" = 20 ] && $TOOL logcheck "$WG" key1 $DX $DY $IW $IH; then
    $TOOL ops "$WG" key1 "$TMP/g_ops.json" &&
      "$VDG" deform "$TMP/g_deform/walk/walker.vdg.json" --frame 20 --key key1 --ops "$TMP/g_ops.json" -q &&
      $TOOL objclose "$TMP/g/walk/key1.obj" "$TMP/g_deform/walk/key1.obj" 1e-5 &&
      "$VDG" eval "$WG" --frame 20 --eye "$($TOOL eye "$WG" key1)" -q -o "$TMP/g_eval.obj" &&
      $TOOL objclose "$TMP/g/walk/key1.obj" "$TMP/g_eval.obj" 1e-5 &&
      pass "(g) the walker's key at frame 20 is vdg deform --frame 20's and vdg eval gives it back there" ||
      fail "(g) the walker's key at frame 20 differs from vdg deform's or from vdg eval's"
  else
    fail "(g) the saved key is not one drag at frame 20: $(grep -A4 key1 "$WG")"
  fi
else
  fail "(g) vdg studio --replay on the walker failed: $(cat "$TMP/g.err")"
fi

# ---- (h) feature lines: L, the model's line then the drawing's, Enter, Ctrl+S == vdg deform's lines op ----
building "$TMP/h"
LX0=$((CX - 40)) LX1=$((CX + 40)) LY=$((CY - 30))
$TOOL events "$TMP/lines.json" $W $H "${ORBIT[@]}" "5:key_down:2" "6:key_up:2" "7:key_down:L" "8:key_up:L" \
  "9:mouse_move:$LX0:$LY" "10:mouse_down:$LX0:$LY" "11:mouse_move:$LX1:$LY" "12:mouse_up:$LX1:$LY" \
  "13:mouse_move:$LX0:$((LY - 14))" "14:mouse_down:$LX0:$((LY - 14))" "15:mouse_move:$LX1:$((LY - 10))" \
  "16:mouse_up:$LX1:$((LY - 10))" "17:key_down:Enter" "18:key_up:Enter" "19:key_down:S:ctrl" "20:key_up:S:ctrl"
if studio "$TMP/h/building.vdg.json" --replay "$TMP/lines.json" 2>"$TMP/h.err" && [ -s "$TMP/h/key1.edits.json" ]; then
  building "$TMP/h_deform"
  python3 -c 'import json, sys; e = json.load(open(sys.argv[1]))["entries"]; sys.exit(not (len(e) == 1 and [o["op"] for o in e[0]["ops"]] == ["lines"] and len(e[0]["ops"][0]["lines"]) == 1))' \
    "$TMP/h/key1.edits.json" &&
    $TOOL ops "$TMP/h/building.vdg.json" key1 "$TMP/h_ops.json" &&
    "$VDG" deform "$TMP/h_deform/building.vdg.json" --key key1 --ops "$TMP/h_ops.json" -q >/dev/null &&
    ! $TOOL objclose "$TMP/h/key1.obj" "$TMP/h/base.obj" 1e-4 >/dev/null 2>&1 &&
    $TOOL objclose "$TMP/h/key1.obj" "$TMP/h_deform/key1.obj" 1e-5 &&
    pass "(h) feature lines drawn in the window give vdg deform's lines key" || fail "(h) the lines key differs or was not logged"
else
  fail "(h) vdg studio --replay of feature lines failed: $(cat "$TMP/h.err")"
fi

# ---- (i) an rbf model: K (where to key needs key triangles) leaves a note instead of ending the session,
# and the Preview blends every key --------------------------------------------------------------------------
mkdir -p "$TMP/i" && cp -r "$SRC"/examples/spot "$TMP/i/"
$TOOL events "$TMP/rbf.json" $W $H "1:key_down:K" "2:key_up:K" "3:key_down:P" "4:key_up:P"
if studio "$TMP/i/spot/spot-rbf.vdg.json" --replay "$TMP/rbf.json" --count 6 --screenshot "$TMP/i.png" 2>"$TMP/i.err" &&
  [ -s "$TMP/i.png" ]; then
  pass "(i) an rbf model: K leaves a note, the Preview draws it"
else
  fail "(i) rbf model: $(cat "$TMP/i.err")"
fi

# ---- usage --------------------------------------------------------------------------------------------
"$VDG" studio "$TMP/a/building.vdg.json" --recover --discard-recovery >/dev/null 2>&1
[ $? -eq 2 ] && pass "usage: --recover with --discard-recovery is exit 2" || fail "usage: expected exit 2"
env -u DISPLAY -u WAYLAND_DISPLAY "$VDG" studio "$TMP/a/building.vdg.json" --count 1 >/dev/null 2>"$TMP/nodisp.err"
rc=$?
[ $rc -eq 1 ] && [ "$(wc -l <"$TMP/nodisp.err")" = 1 ] && pass "no display: one line, exit 1" ||
  fail "no display: exit $rc, '$(cat "$TMP/nodisp.err")'"

exit $FAILED
