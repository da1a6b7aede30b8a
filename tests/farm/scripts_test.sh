#!/usr/bin/env bash
# scripts/farm/submit and render-array.sbatch without a cluster: submit --dry-run's slices (every
# frame in exactly one slice, sizes within one frame), each array task's vdg command line (the
# script run directly with SLURM_ARRAY_TASK_ID set and a stand-in vdg that prints its arguments),
# and every usage error with its one-line message and exit status 2.
#
# Usage: scripts_test.sh SOURCE_DIR WORK_DIR
set -euo pipefail

[ $# -eq 2 ] || {
  echo "usage: scripts_test.sh SOURCE_DIR WORK_DIR" >&2
  exit 2
}
source_dir=$(cd "$1" && pwd)
work=$2
submit=$source_dir/scripts/farm/submit
array=$source_dir/scripts/farm/render-array.sbatch
rm -rf "$work"
mkdir -p "$work"
failures=0

fail() {
  echo "FAIL: $*" >&2
  failures=$((failures + 1))
}

# A stand-in vdg: prints its arguments, one a line.
fake_vdg=$work/vdg
printf '#!/usr/bin/env bash\nprintf "%%s\\n" "$@"\n' >"$fake_vdg"
chmod +x "$fake_vdg"

# The slices submit --dry-run prints for --frames FRAMES --tasks N, as "a-b,c-d,...".
slices_of() {
  "$submit" --frames "$1" --tasks "$2" --vdg "$fake_vdg" --dry-run -- run shot.lua 2>&1 >/dev/null |
    sed -n 's/^submit: frames .* in [0-9]* tasks: //p'
}

expect_slices() {
  local got
  got=$(slices_of "$1" "$2")
  [ "$got" = "$3" ] || fail "--frames $1 --tasks $2: slices '$got', expected '$3'"
}
expect_slices 0-39 4 "0-9,10-19,20-29,30-39"
expect_slices 0-10 3 "0-2,3-6,7-10"
expect_slices 5-7 4 "5-5,6-6,7-7"  # more tasks than frames: one frame a task
expect_slices 12 2 "12-12"
expect_slices 100-100 1 "100-100"
expect_slices 0-959 16 "0-59,60-119,120-179,180-239,240-299,300-359,360-419,420-479,480-539,540-599,600-659,660-719,720-779,780-839,840-899,900-959"

# Property: for many ranges and task counts, the slices cover the range in order, each frame
# exactly once, and their sizes differ by at most one.
for range in 0-0 3-12 7-106 0-999; do
  for tasks in 1 3 7 64; do
    first=${range%-*} last=${range#*-}
    next=$first min=999999 max=0 count=0
    IFS=, read -r -a parts <<<"$(slices_of "$range" "$tasks")"
    for part in "${parts[@]}"; do
      a=${part%-*} b=${part#*-}
      [ "$a" -eq "$next" ] || fail "--frames $range --tasks $tasks: slice $part does not start at $next"
      size=$((b - a + 1))
      [ "$size" -ge 1 ] || fail "--frames $range --tasks $tasks: empty slice $part"
      ((size < min)) && min=$size
      ((size > max)) && max=$size
      next=$((b + 1))
      count=$((count + 1))
    done
    [ "$next" -eq $((last + 1)) ] || fail "--frames $range --tasks $tasks: slices end at $((next - 1)), not $last"
    [ $((max - min)) -le 1 ] || fail "--frames $range --tasks $tasks: slice sizes from $min to $max"
    expected_tasks=$((tasks < last - first + 1 ? tasks : last - first + 1))
    [ "$count" -eq "$expected_tasks" ] || fail "--frames $range --tasks $tasks: $count slices, expected $expected_tasks"
  done
done

# The sbatch command: --array over the slices (and %M), --wait, sbatch options, then the script,
# the slices, the absolute vdg and the vdg arguments as given.
command=$("$submit" --frames 0-9 --tasks 2 --vdg "$fake_vdg" --max-running 1 --wait \
  --sbatch --partition=render --dry-run -- render "my model.vdg.json" -o out 2>/dev/null)
expected=$(printf '%q ' sbatch --parsable --array=0-1%1 --wait --partition=render "$array" 0-4,5-9 \
  "$fake_vdg" render "my model.vdg.json" -o out)
[ "$command" = "$expected" ] || fail "dry-run command: got '$command', expected '$expected'"
# A relative --vdg is made absolute (the nodes do not share the submitting shell's folder).
command=$(cd "$work" && "$submit" --frames 0-1 --tasks 1 --vdg ./vdg --dry-run -- run a.lua 2>/dev/null)
[[ $command == *" $work/vdg run a.lua "* ]] || fail "relative --vdg not made absolute: '$command'"

# Each array task runs vdg with its slice appended as --frames.
for task in 0 1 2; do
  got=$(SLURM_ARRAY_TASK_ID=$task "$array" 0-9,10-19,20-25 "$fake_vdg" run "a b.lua" -o out 2>/dev/null | tr '\n' ' ')
  slice=$(cut -d, -f$((task + 1)) <<<"0-9,10-19,20-25")
  [ "$got" = "run a b.lua -o out --frames $slice " ] || fail "array task $task ran vdg with '$got'"
done
# ... and exits with vdg's status.
status=0
SLURM_ARRAY_TASK_ID=0 "$array" 0-9 false run a.lua 2>/dev/null || status=$?
[ "$status" -eq 1 ] || fail "array task with a failing vdg: exit status $status, expected 1"

# Usage errors: exit status 2 and a message naming the problem.
expect_usage_error() {
  local what=$1 needle=$2 out status=0
  shift 2
  out=$("$@" 2>&1 >/dev/null) || status=$?
  [ "$status" -eq 2 ] || fail "$what: exit status $status, expected 2 (stderr: $out)"
  [[ $out == *"$needle"* ]] || fail "$what: message '$out' does not say '$needle'"
}
v=(--vdg "$fake_vdg")
expect_usage_error "no --frames" "--frames A-B is required" "$submit" --tasks 2 "${v[@]}" -- run a.lua
expect_usage_error "bad --frames" "--frames 'x-3' is not A-B" "$submit" --frames x-3 --tasks 2 "${v[@]}" -- run a.lua
expect_usage_error "negative --frames" "--frames '-1-3' is not A-B" "$submit" --frames -1-3 --tasks 2 "${v[@]}" -- run a.lua
expect_usage_error "reversed --frames" "A must not be greater than B" "$submit" --frames 9-3 --tasks 2 "${v[@]}" -- run a.lua
expect_usage_error "no --tasks" "--tasks N is required" "$submit" --frames 0-9 "${v[@]}" -- run a.lua
expect_usage_error "zero --tasks" "--tasks N is required, a whole number >= 1 (got '0')" "$submit" --frames 0-9 --tasks 0 "${v[@]}" -- run a.lua
expect_usage_error "bad --max-running" "--max-running '0'" "$submit" --frames 0-9 --tasks 2 --max-running 0 "${v[@]}" -- run a.lua
expect_usage_error "option without value" "--sbatch needs a value" "$submit" --frames 0-9 --tasks 2 --sbatch
expect_usage_error "unknown option" "unknown option '--nodes'" "$submit" --frames 0-9 --tasks 2 --nodes 3 -- run a.lua
expect_usage_error "no subcommand" "the vdg subcommand is missing" "$submit" --frames 0-9 --tasks 2 "${v[@]}" --
expect_usage_error "bad subcommand" "must be run or render, not 'export'" "$submit" --frames 0-9 --tasks 2 "${v[@]}" -- export m.vdg.json
expect_usage_error "--frames after --" "give the frames with submit's --frames" "$submit" --frames 0-9 --tasks 2 "${v[@]}" -- run a.lua --frames 3-4
expect_usage_error "missing --vdg file" "--vdg '$work/nothing' is not an executable file" "$submit" --frames 0-9 --tasks 2 --vdg "$work/nothing" -- run a.lua
expect_usage_error "vdg not on PATH" "vdg is not on PATH: give --vdg PATH" env PATH=/nonexistent "$BASH" "$submit" --frames 0-9 --tasks 2 -- run a.lua

expect_usage_error "array: too few arguments" "usage: render-array.sbatch SLICES VDG" env SLURM_ARRAY_TASK_ID=0 "$array" 0-9 "$fake_vdg"
expect_usage_error "array: bad subcommand" "SUBCOMMAND must be run or render, not 'eval'" env SLURM_ARRAY_TASK_ID=0 "$array" 0-9 "$fake_vdg" eval m
expect_usage_error "array: --frames given" "give the frames in SLICES" env SLURM_ARRAY_TASK_ID=0 "$array" 0-9 "$fake_vdg" run a.lua --frames=1-2
expect_usage_error "array: not an array task" "not an array task" env -u SLURM_ARRAY_TASK_ID "$array" 0-9 "$fake_vdg" run a.lua
expect_usage_error "array: task without a slice" "array task 2 has no slice: SLICES '0-4,5-9' has 2 (use --array=0-1)" env SLURM_ARRAY_TASK_ID=2 "$array" 0-4,5-9 "$fake_vdg" run a.lua
expect_usage_error "array: bad slice" "slice 1 '5-x' is not A-B or N" env SLURM_ARRAY_TASK_ID=1 "$array" 0-4,5-x "$fake_vdg" run a.lua

if [ "$failures" -ne 0 ]; then
  echo "scripts_test: $failures failure(s)" >&2
  exit 1
fi
echo "scripts_test: submit and render-array.sbatch behave"
