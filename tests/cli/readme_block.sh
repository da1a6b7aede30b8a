#!/usr/bin/env bash
# Runs every command of a documentation block as a newcomer would type it:
#   readme_block.sh BIN_DIR SOURCE_DIR [DOC [HEADING]]
# DOC (default README.md) is read from SOURCE_DIR; the first ```sh block after the line "HEADING"
# (default "## Using it"; "" for every ```sh block of DOC) is run line by line with bash, B set to
# BIN_DIR (a line "B=..." of the block is replaced by it, and "vdg " at the start of a line means
# "$B/vdg "), in a temporary folder holding a copy of SOURCE_DIR/examples, so that the repository is
# never written. Any failing line fails the test, naming the line.
# `vdg studio` opens a window: on a virtual X server (Xvfb, when installed) it runs as written plus
# --count 2 (it then closes by itself); without Xvfb it is skipped with a note, unless
# VDG_REQUIRE_XVFB=1.
set -euo pipefail
bin=$(cd "$1" && pwd)
src=$(cd "$2" && pwd)
doc=${3:-README.md}
heading=${4-"## Using it"}

work=$(mktemp -d)
xvfb_pid=
trap '[ -z "$xvfb_pid" ] || kill "$xvfb_pid" 2>/dev/null; rm -rf "$work"' EXIT
cp -r "$src/examples" "$work/examples"

# The block's lines: from the heading (or the top) to the end of the first ```sh fence after it.
lines=$(awk -v heading="$heading" '
  heading == "" || $0 == heading { armed = 1 }
  armed && /^```sh$/ { inside = 1; next }
  inside && /^```$/ { inside = 0; if (heading != "") exit; next }
  inside { print }
' "$src/$doc")
[ -n "$lines" ] || { echo "readme_block: no \`\`\`sh block under '$heading' in $doc" >&2; exit 1; }

cd "$work"
count=0
while IFS= read -r line; do
  case "$line" in
    "" | "#"*) continue ;;
    B=*) continue ;;  # B is the build's bin folder here
  esac
  cmd=$line
  case "$cmd" in vdg\ *) cmd="\$B/$cmd" ;; esac
  if [[ "$cmd" == *'/vdg studio'* || "$cmd" == *'/vdg'*' studio '* ]]; then
    if ! "$bin/vdg" studio --help >/dev/null 2>&1; then
      echo "readme_block: skipped (this build has no vdg studio: GLFW or Dear ImGui missing): $line"
      continue
    elif command -v Xvfb >/dev/null; then
      if [ -z "$xvfb_pid" ]; then  # one X server, on a free display it reports once ready
        Xvfb -displayfd 3 -screen 0 1600x1000x24 -nolisten tcp 3>"$work/.display" 2>"$work/.xvfb.err" &
        xvfb_pid=$!
        for _ in $(seq 100); do [ -s "$work/.display" ] && break; sleep 0.1; done
        [ -s "$work/.display" ] || { echo "readme_block: Xvfb did not start: $(cat "$work/.xvfb.err")" >&2; exit 1; }
      fi
      cmd="DISPLAY=:$(head -1 "$work/.display") ${cmd%%#*} --count 2"
    elif [ "${VDG_REQUIRE_XVFB:-}" = 1 ]; then
      echo "readme_block: VDG_REQUIRE_XVFB=1 but Xvfb is not installed (scripts/install-deps)" >&2
      exit 1
    else
      echo "readme_block: skipped (vdg studio needs a display; install xvfb to run it): $line"
      continue
    fi
  fi
  count=$((count + 1))
  if ! out=$(B="$bin" bash -euo pipefail -c "$cmd" 2>&1 </dev/null); then
    echo "readme_block: $doc: this line failed:" >&2
    echo "  $line" >&2
    echo "$out" | tail -n 20 >&2
    exit 1
  fi
done <<<"$lines"
echo "readme_block: $doc: $count lines ran"
