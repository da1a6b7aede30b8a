#!/usr/bin/env bash
# scripts/validate-gltf as a user runs it, and the files the repository ships as glTF:
#   validate_gltf_test.sh REPO_ROOT WORK_DIR
# Exit 0 when every check passes, 1 on the first failure (naming it), 77 (CTest: skipped) when the
# validator is not installed (scripts/install-deps installs it).
# Data: tests/tools/data/triangle.gltf + triangle.bin (a valid file with an external buffer) and
# triangle_warning.gltf (the same with one unexpected property: a warning, no error); hand-written.
set -uo pipefail
root=$1
work=$2
validate=$root/scripts/validate-gltf
data=$root/tests/tools/data

if ! command -v node >/dev/null || [ ! -d "$root/tools/gltf-validator/node_modules/gltf-validator" ]; then
  if [ "${VDG_REQUIRE_GLTF_VALIDATOR:-0}" = 1 ]; then
    echo "FAILED: VDG_REQUIRE_GLTF_VALIDATOR=1 but the glTF validator is not installed (run scripts/install-deps)"
    exit 1
  fi
  echo "SKIPPED: the glTF validator is not installed (run scripts/install-deps)"
  exit 77
fi
rm -rf "$work" && mkdir -p "$work"

failures=0
# expect STATUS PATTERN -- ARGS...: runs validate-gltf ARGS, checks its exit status and that its
# output (stdout and stderr) contains PATTERN (a fixed string; empty = no check).
expect() {
  local want=$1 pattern=$2
  shift 3
  local out status
  out=$("$validate" "$@" 2>&1)
  status=$?
  if [ "$status" -ne "$want" ]; then
    echo "FAIL: validate-gltf $* exited $status, expected $want; output:"
    echo "$out"
    failures=$((failures + 1))
  elif [ -n "$pattern" ] && ! grep -qF -- "$pattern" <<<"$out"; then
    echo "FAIL: validate-gltf $* did not print '$pattern'; output:"
    echo "$out"
    failures=$((failures + 1))
  else
    echo "ok: validate-gltf $* -> $status"
  fi
}

# Valid files, including an external buffer resolved relative to the file (not the working dir).
expect 0 "triangle.gltf: 0 errors, 0 warnings" -- "$data/triangle.gltf"
(cd / && "$validate" "$data/triangle.gltf" >/dev/null) || { echo "FAIL: external buffer from /"; failures=$((failures + 1)); }
# The walking character must be clean: no errors and no warnings.
expect 0 "walker.glb: 0 errors, 0 warnings" -- --strict "$root/examples/walk/walker.glb"
# Several files: one summary line each.
expect 0 "walker.glb: 0 errors" -- "$data/triangle.gltf" "$root/examples/walk/walker.glb"

# A warning passes, except with --strict; it is printed with its pointer.
expect 0 "WARNING UNEXPECTED_PROPERTY /asset/unexpected" -- "$data/triangle_warning.gltf"
expect 1 "WARNING UNEXPECTED_PROPERTY /asset/unexpected" -- --strict "$data/triangle_warning.gltf"

# Errors: a missing external buffer, a truncated GLB, not glTF at all, a file that does not exist.
cp "$data/triangle.gltf" "$work/lonely.gltf"
expect 1 "ERROR IO_ERROR /buffers/0/uri" -- "$work/lonely.gltf"
head -c 1000 "$root/examples/walk/walker.glb" >"$work/truncated.glb"
expect 1 "truncated.glb: 1 errors" -- "$work/truncated.glb"
echo "hello" >"$work/hello.glb"
expect 1 "hello.glb: not glTF or GLB" -- "$work/hello.glb"
expect 1 "missing.gltf: cannot read" -- "$work/missing.gltf"
# One bad file among good ones fails the run, and the good ones are still reported.
expect 1 "triangle.gltf: 0 errors" -- "$work/lonely.gltf" "$data/triangle.gltf"

# Bad usage.
expect 2 "no FILE given" --
expect 2 "unknown option '--bogus'" -- --bogus "$data/triangle.gltf"

if [ "$failures" -ne 0 ]; then
  echo "$failures check(s) failed"
  exit 1
fi
