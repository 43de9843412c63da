#!/usr/bin/env bash
# Runs the three fuzzers side by side for SECONDS each: run.sh BUILD_DIR SECONDS. Exits non-zero on any
# crash, hang, leak or sanitizer report; the input that did it is kept in BUILD_DIR/fuzz-artifacts/.
set -uo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
build="$(cd "$1" && pwd)"
seconds="$2"
"$here/make_corpus.sh" "$build/fuzz-seeds"
# Snapshot seeds: the default scene's state at a few steps, without the saved-state header.
mkdir -p "$build/fuzz-seeds/snapshot"
for steps in 0 5 60 200; do
  "$build/ballbox" sim --steps "$steps" --save-state "$build/fuzz-seeds/state" >/dev/null
  tail -c +17 "$build/fuzz-seeds/state" >"$build/fuzz-seeds/snapshot/default_$steps"
done
# And a world with every kind of part, under the default scene's settings (the same fingerprint).
for steps in 0 30 120; do
  "$build/ballbox" sim "$here/snapshot_parts_scene.json" --steps "$steps" --save-state "$build/fuzz-seeds/state" >/dev/null
  tail -c +17 "$build/fuzz-seeds/state" >"$build/fuzz-seeds/snapshot/parts_$steps"
done
rm -f "$build/fuzz-seeds/state"
mkdir -p "$build/fuzz-artifacts"
pids=()
names=(scene script snapshot)
for name in "${names[@]}"; do
  # The first folder collects what the fuzzer finds (kept between runs); the seeds are read only.
  mkdir -p "$build/fuzz-corpus/$name"
  "$build/fuzz_$name" "$build/fuzz-corpus/$name" "$build/fuzz-seeds/$name" \
    $([ -f "$here/$name.dict" ] && echo "-dict=$here/$name.dict") -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -max_len=8192 -print_final_stats=1 -artifact_prefix="$build/fuzz-artifacts/$name-" \
    >"$build/fuzz-$name.log" 2>&1 &
  pids+=($!)
done
status=0
for i in 0 1 2; do
  name=${names[$i]}
  if wait "${pids[$i]}"; then
    echo "fuzz_$name: no crash in ${seconds} s:" \
      "$(grep -E '^stat::number_of_executed_units' "$build/fuzz-$name.log" | awk '{print $2}') runs," \
      "corpus $(ls "$build/fuzz-corpus/$name" | wc -l) inputs"
  else
    status=1
    echo "fuzz_$name: FAILED; the log's end ($build/fuzz-$name.log):"
    tail -n 60 "$build/fuzz-$name.log"
  fi
done
exit $status
