#!/usr/bin/env bash
# Runs every asset scene through two builds of `ballbox sim` and compares their state hashes:
# make test-arm64 (native against qemu-aarch64) and make test-compilers (GCC against Clang).
# usage: .ci/compare_hashes.sh STEPS REFERENCE_NAME REFERENCE_BALLBOX NAME COMMAND...
#   COMMAND is the other ballbox, with any runner before it (qemu-aarch64 build-arm64/ballbox).
# Prints a table and "NAME: P passed, F failed"; exits 1 on any difference or failed run.
set -uo pipefail
cd "$(dirname "$0")/.."
if [ $# -lt 5 ]; then
  sed -n '4,6p' "$0" >&2
  exit 2
fi
steps=$1 reference_name=$2 reference=$3 name=$4
shift 4
other=("$@")

# The built-in scene with its demo script (no scene argument), the same scene from its file
# (no script), then every example scene.
runs=("" assets/default.json assets/scenes/*.json)

# The state hash `ballbox sim` prints last, or what went wrong.
hash_of() {
  local out
  if ! out=$("$@" 2>&1); then
    echo "failed (${out##*$'\n'})"
    return
  fi
  echo "${out##*state-hash: }"
}

passed=0 failed=0
printf '%-45s %-18s %-18s %s\n' "scene ($steps steps)" "$reference_name" "$name" "result"
for scene in "${runs[@]}"; do
  args=(sim ${scene:+"$scene"} --steps "$steps")
  want=$(hash_of "$reference" "${args[@]}")
  got=$(hash_of "${other[@]}" "${args[@]}")
  if [[ $want =~ ^[0-9a-f]{16}$ && $want == "$got" ]]; then
    result=same passed=$((passed + 1))
  else
    result=DIFFERENT failed=$((failed + 1))
  fi
  printf '%-45s %-18s %-18s %s\n' "${scene:-(built-in scene and demo script)}" "$want" "$got" "$result"
done
echo "$name: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
