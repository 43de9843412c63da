#!/usr/bin/env bash
# `make bench`: runs every benchmark program into OUT (bench-out/), draws the plots into docs/img/
# and rebuilds docs/benchmarks.md from bench/plots/benchmarks.md.in with the programs' own tables.
# Usage: bench/plots/make_page.sh BUILD_DIR [OUT_DIR]   (from the repository root)
set -euo pipefail
build=${1:?usage: make_page.sh BUILD_DIR [OUT_DIR]}
out=${2:-bench-out}
img=docs/img
page=docs/benchmarks.md
template=bench/plots/benchmarks.md.in
mkdir -p "$out" "$img"
started=$(date -u '+%Y-%m-%d %H:%M UTC')

# BENCH_PAGE_ONLY=1 rewrites the page from the template and the outputs already in OUT (after an
# edit of the template's prose), running and plotting nothing.
if [[ "${BENCH_PAGE_ONLY:-0}" != 1 ]]; then
  # Timings are only worth keeping on a quiet machine: wait (up to BENCH_WAIT_MINUTES, default 30)
  # for the 1-minute load average to drop below BENCH_MAX_LOAD (default 2), then run anyway and say so.
  max_load=${BENCH_MAX_LOAD:-2}
  wait_minutes=${BENCH_WAIT_MINUTES:-30}
  quiet() { awk -v max="$max_load" '{exit !($1 < max)}' /proc/loadavg; }
  for ((i = 0; i < wait_minutes * 2; i++)); do
    quiet && break
    echo "bench: load average $(cut -d' ' -f1-3 /proc/loadavg) is not below $max_load; waiting" >&2
    sleep 30
  done
  quiet || echo "bench: running with load average $(cut -d' ' -f1-3 /proc/loadavg) (the tables state it)" >&2

  run() {  # name, then the program's arguments: stdout kept as OUT/name.txt for the page
    local name=$1
    shift
    echo "bench: $name" >&2
    "$build/$name" "$@" > "$out/$name.txt"
  }
  run bench_work_precision --out "$out"
  run bench_solver --out "$out"
  run bench_peers --out "$out"
  run bench_scaling --out "$out"
  run bench_skip --out "$out"
  run bench_broadphase --out "$out"
  run bench_render --out "$out/render"
  run bench_particles --out "$out/particles"
  run bench_threads --out "$out"

  echo "bench: plots -> $img" >&2
  for plot in work_precision stability scaling peers; do
    gnuplot -e "dir='$out'; img='$img'" "bench/plots/$plot.gp"
  done
  # docs/img/broadphase.png belongs to docs/broadphase.md (figures copied by hand): this page draws its own.
  gnuplot -e "csv='$out/broadphase_bench.csv'; out='$img/benchmarks_broadphase.png'" bench/broadphase_plot.gp
fi

# The page: @@HEADER name@@ becomes the lines a program printed before its first blank line (the
# run, the machine, the load) in a text block; @@TABLES name@@ everything after it but the CSV
# note, copied as printed, up to bench_peers' solver-setting sweep, which @@SWEEP name@@ places
# on its own; @@RUN@@ the commit and date of this run.
commit=$(git rev-parse --short HEAD 2>/dev/null || echo unknown)
dirty=$(git status --porcelain --untracked-files=no 2>/dev/null | grep -q . && echo " (uncommitted changes in the tree)" || true)
run_line="Measured from $started at commit $commit$dirty on Debian $(cat /etc/debian_version 2>/dev/null || echo '?')."
# The run the outputs came from, kept beside them for a page-only rewrite.
if [[ "${BENCH_PAGE_ONLY:-0}" == 1 && -f "$out/run.txt" ]]; then
  run_line=$(cat "$out/run.txt")
else
  echo "$run_line" > "$out/run.txt"
fi
awk -v out="$out" -v run_line="$run_line" '
  function header(file,   line) {
    print "```text"
    while ((getline line < file) > 0) { if (line == "") break; print line }
    close(file)
    print "```"
  }
  function body(file, sweep,   line, started, in_sweep) {
    started = 0; in_sweep = 0
    while ((getline line < file) > 0) {
      if (!started) { if (line == "") started = 1; continue }
      if (line ~ /^ballbox.s solver settings/) { in_sweep = 1; continue }
      if (line ~ /^CSV: /) continue
      if (in_sweep == sweep) print line
    }
    close(file)
  }
  /^@@HEADER [a-z_]+@@$/ { name = $2; sub(/@@$/, "", name); header(out "/" name ".txt"); next }
  /^@@TABLES [a-z_]+@@$/ { name = $2; sub(/@@$/, "", name); body(out "/" name ".txt", 0); next }
  /^@@SWEEP [a-z_]+@@$/ { name = $2; sub(/@@$/, "", name); body(out "/" name ".txt", 1); next }
  /^@@RUN@@$/ { print run_line; next }
  { print }
' "$template" > "$page.tmp"
mv "$page.tmp" "$page"
echo "bench: $page, $img/*.png, CSV in $out/" >&2
