#!/usr/bin/env bash
# Runs both fuzzers side by side for SECONDS each: run.sh BUILD_DIR SECONDS. Exits non-zero on any
# crash, hang, leak or sanitizer report; the input that did it is kept in BUILD_DIR/fuzz-artifacts/.
set -uo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
build="$(cd "$1" && pwd)"
seconds="$2"
"$here/make_corpus.sh" "$build/fuzz-seeds"
mkdir -p "$build/fuzz-artifacts"
pids=()
for name in scene script; do
  # The first folder collects what the fuzzer finds (kept between runs); the seeds are read only.
  mkdir -p "$build/fuzz-corpus/$name"
  "$build/fuzz_$name" "$build/fuzz-corpus/$name" "$build/fuzz-seeds/$name" \
    -dict="$here/$name.dict" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -max_len=8192 -print_final_stats=1 -artifact_prefix="$build/fuzz-artifacts/$name-" \
    >"$build/fuzz-$name.log" 2>&1 &
  pids+=($!)
done
status=0
for i in 0 1; do
  name=$([ $i -eq 0 ] && echo scene || echo script)
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
