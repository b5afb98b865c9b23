#!/bin/bash
# Instructions a boolean call takes (issue 16): the `calls` example under valgrind's
# callgrind, on one thread, counted at two numbers of calls and differenced, so that
# reading and checking the inputs drop out. Unlike times, the count does not drift with
# the machine's load or clock: changes of a few per cent show in one run.
#
#   cargo build --release -p meshbool --example calls
#   bench/instructions.sh A.stl B.stl [union|intersection|difference] [BINARY ...]
#
# Prints one line per binary (default: target/release/examples/calls): instructions per
# call. Needs valgrind.
set -eu
a=$1 b=$2 op=${3:-intersection}
shift $(( $# < 3 ? $# : 3 ))
bins=("$@")
[ ${#bins[@]} -eq 0 ] && bins=(target/release/examples/calls)
count() { # binary calls -> instructions of the whole run (three rounds of `calls`)
  RAYON_NUM_THREADS=1 valgrind --tool=callgrind --callgrind-out-file=/dev/null \
    "$1" "$a" "$b" "$op" "$2" 2>&1 | awk '/Collected/ {print $4}'
}
for bin in "${bins[@]}"; do
  lo=$(count "$bin" 20) hi=$(count "$bin" 60)
  echo "$bin: $(( (hi - lo) / 120 )) instructions a call ($op)"
done
