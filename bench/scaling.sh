#!/bin/bash
# Scaling with cores (issue 20): the file-to-file union of a mesh pair at 1, 2, 4, 8 and 16
# threads, each pinned with taskset to as many cores, with `--timings` per stage.
#
#   bench/scaling.sh MESHBOOL A.stl B.stl [OTHER_MESHBOOL]
#
# Prints per run: the label, threads, wall seconds of the whole process, then the stages'
# seconds (read and check, intersect, cut, classify, merge, write, in all). With a second
# binary (e.g. main's), both run alternately (each going first once) and their outputs are
# compared byte for byte.
set -u
bin=$1 a=$2 b=$3 other=${4:-}
out=${TMPDIR:-/tmp}/meshbool-scaling-$$
TIMEFORMAT='%R'
run() { # label binary threads
  local w
  w=$( { time taskset -c 0-$(($3 - 1)) "$2" union "$a" "$b" -o "$out-$1.stl" --threads "$3" \
    --no-self-check --timings > /dev/null 2> "$out.err"; } 2>&1 )
  echo "$1 threads $3 wall $w | $(grep -E '^ +[0-9]' "$out.err" | awk '{print $1}' | paste -sd' ' -)"
}
echo "stages: read intersect cut classify merge write all"
for n in ${THREADS:-1 2 4 8 16}; do
  [ "$n" -gt "$(nproc)" ] && continue
  # The two binaries take turns going first: in one process after the other, the first
  # was measured slower in a stage whose code both share (intersect, ~25 ms at 4 threads).
  for r in 1 2; do
    if [ -n "$other" ] && [ "$r" = 1 ]; then run other "$other" "$n"; fi
    run this "$bin" "$n"
    if [ -n "$other" ] && [ "$r" = 2 ]; then run other "$other" "$n"; fi
  done
  [ -n "$other" ] && { cmp -s "$out-other.stl" "$out-this.stl" && echo "same output" || echo "OUTPUTS DIFFER"; }
done
rm -f "$out"-*.stl "$out.err"
