#!/bin/bash
# vdg view as a user runs it (docs/web.md), without a browser: the folder written and replaced whole,
# what it refuses (exit 1 for bad input, 2 for bad usage, one line naming the file or option), the
# web files found through VDG_WEB_DIR and the message when three.js is missing, and --serve answering
# and stopping on Ctrl-C (SIGINT) with status 0.
# Usage: view_cli.sh VDG SOURCE_DIR WORK_DIR
set -u
vdg=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
spot=$src/examples/spot/spot.vdg.json
failures=0
check() {  # check WHAT COMMAND...: the command must succeed
  local what=$1; shift
  if "$@"; then echo "ok   $what"; else echo "FAIL $what"; failures=$((failures + 1)); fi
}
# expect STATUS PATTERN WHAT -- ARGS...: vdg ARGS exits with STATUS and prints one stderr line matching PATTERN
expect() {
  local status=$1 pattern=$2 what=$3; shift 4
  "$vdg" "$@" >/dev/null 2>"$work/stderr"
  local got=$? err; err=$(grep -v '^vdg: note' "$work/stderr")
  if [ "$got" = "$status" ] && [ "$(printf '%s\n' "$err" | wc -l)" = 1 ] && [[ $err =~ $pattern ]]; then
    echo "ok   $what"
  else
    echo "FAIL $what: exit $got, stderr: $err"; failures=$((failures + 1))
  fi
}

check "vdg view writes the folder" "$vdg" view "$spot" -o "$work/site" -q
for f in index.html view.js vdg-three.js model.glb three/three.module.js three/three.core.js \
         three/addons/loaders/GLTFLoader.js three/addons/controls/OrbitControls.js .vdg-view; do
  check "  with $f" test -s "$work/site/$f"
done
touch "$work/site/stale.txt"
check "a second vdg view replaces its own folder whole" "$vdg" view "$spot" -o "$work/site" -q
check "  (the old files are gone)" test ! -e "$work/site/stale.txt"
check "  and leaves no staging folder" test -z "$(ls -A "$work" | grep -v '^site$')"
mkdir -p "$work/mine" && echo keep > "$work/mine/notes.txt"
expect 1 "mine: is a folder vdg view did not write" "refuses a folder it did not write" -- view "$spot" -o "$work/mine"
check "  and leaves it alone" grep -q keep "$work/mine/notes.txt"
echo x > "$work/afile"
expect 1 "afile: is a file" "refuses a file as the folder" -- view "$spot" -o "$work/afile"
expect 1 "an OBJ mesh" "refuses a plain mesh" -- view "$src/examples/spot/spot.obj" -o "$work/m"
expect 1 "no-such.vdg.json" "names a missing model" -- view "$work/no-such.vdg.json" -o "$work/m"
expect 2 "give -o DIR, or --serve" "needs -o or --serve" -- view "$spot"
expect 2 "--port needs --serve" "--port needs --serve" -- view "$spot" -o "$work/p" --port 9000
expect 2 "--port" "refuses a bad port" -- view "$spot" --serve --port 70000
mkdir -p "$work/web/view" && cp "$src/web/view/index.html" "$work/web/view/" && cp "$src/web/vdg-three.js" "$work/web/"
VDG_WEB_DIR=$work/web expect 1 "three.js is missing.*scripts/install-deps" "says to run install-deps without three.js" \
  -- view "$spot" -o "$work/n"
VDG_WEB_DIR=$work/nowhere expect 1 "VDG_WEB_DIR=.*not vdg's web folder" "names a bad VDG_WEB_DIR" -- view "$spot" -o "$work/n"
check "  and wrote nothing" test ! -e "$work/n"

# --serve: answers, then stops on SIGINT with status 0.
"$vdg" view "$spot" -o "$work/served" --serve --port 0 -q >"$work/serve.out" 2>"$work/serve.err" &
pid=$!
for _ in $(seq 100); do grep -q 'http://' "$work/serve.out" && break; sleep 0.1; done
url=$(grep -o 'http://127.0.0.1:[0-9]*/' "$work/serve.out")
check "--serve prints its address" test -n "$url"
if command -v curl >/dev/null; then
  check "  and serves view.js as text/javascript" \
    sh -c "curl -s -D - -o /dev/null '${url}view.js' | grep -qi '^content-type: text/javascript'"
  check "  and refuses to leave the folder" \
    sh -c "curl -s --path-as-is -o /dev/null -w '%{http_code}' '${url}../../../etc/passwd' | grep -q 404"
  check "  and answers a request head over 8 KiB with 431" \
    sh -c "curl -s -o /dev/null -w '%{http_code}' -H 'X: $(printf '%9000s' | tr ' ' a)' '${url}' | grep -q 431"
fi
kill -INT $pid
wait $pid
check "Ctrl-C stops the server with status 0" test $? = 0
[ $failures = 0 ] && echo "all passed" || echo "$failures failed"
exit $((failures > 0))
