#!/usr/bin/env bash
# Coverage-guided fuzzing with ASan/UBSan for a fixed time per target (ctest `fuzz_sanitized`,
# label fuzz): configures a clang build with -DCLOUDBRUSH_FUZZ=ON under WORK_DIR (once; ccache
# when present), builds only the given targets, and runs each with libFuzzer's
# -max_total_time=SECONDS on a scratch copy of its corpus (tests/fuzz/NAME/corpus is read, never
# written). A crash, leak, sanitizer report or timeout fails; its input is kept under
# WORK_DIR/artifacts/TARGET/. Per target it prints libFuzzer's seed (CB_FUZZ_SEED when set, so a
# failure reruns with the same mutations) and its last status: inputs run (#N), edges (cov) and
# features (ft) covered, the corpus kept.
#
# The clang build is a unity build (CMAKE_UNITY_BUILD): the parsers' libraries reach most of
# the app (journal_replay replays whole sessions), and one translation unit per eight sources
# parses the standard library an eighth as often — with a cold ccache the build dominates.
#
#   run_sanitized_fuzzers.sh SOURCE_DIR WORK_DIR SECONDS TARGET...
set -euo pipefail
src=${1:?source dir}; work=${2:?work dir}; secs=${3:?seconds per target}; shift 3
if ! command -v clang++ >/dev/null; then
  echo "*** SKIPPED: clang++ is not installed; no sanitized fuzzing ran (config/setup.sh) ***" >&2
  exit 77
fi
mkdir -p "$work"
build=$work/build
launcher=()
if command -v ccache >/dev/null; then
  launcher=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
# ccache keys on paths below this folder relative to it; with -g it also hashes the build folder
# (hash_dir), so another clone hits only with CCACHE_NOHASHDIR=1. The same build folder always hits.
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$(dirname "$(cd "$src" && pwd)")}
start=$(date +%s)
# configure_and_build DIR UNITY TARGET...: the clang build in DIR (configured once).
configure_and_build() {
  local dir=$1 unity=$2; shift 2
  if [ ! -f "$dir/build.ninja" ]; then
    if ! CC=clang CXX=clang++ cmake -S "$src" -B "$dir" -G Ninja -DCLOUDBRUSH_FUZZ=ON \
        -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_UNITY_BUILD="$unity" "${launcher[@]}" \
        >"$work/configure.log" 2>&1; then
      tail -30 "$work/configure.log"
      echo "sanitized fuzzing: configuring the clang build failed ($work/configure.log)" >&2
      exit 1
    fi
  fi
  ninja -C "$dir" "$@" >"$work/build.log" 2>&1
}
if ! configure_and_build "$build" ON "$@"; then
  # Two sources of one library defining the same file-local name break only the unity build:
  # say so, and fuzz from a plain build (slower) rather than not at all.
  grep -E 'error: (redefinition|conflicting|call to .* is ambiguous)' "$work/build.log" | head -5
  echo "sanitized fuzzing: the unity build failed; list one of the two sources in" \
    "cb_unity_alone (tests/fuzz/sanitized/CMakeLists.txt). Building without unity." >&2
  build=$work/build-plain
  if ! configure_and_build "$build" OFF "$@"; then
    tail -40 "$work/build.log"
    echo "sanitized fuzzing: building the targets failed ($work/build.log)" >&2
    exit 1
  fi
fi
echo "sanitized fuzzing: clang -fsanitize=fuzzer,address,undefined build ready in $(( $(date +%s) - start )) s"
fuzz_start=$(date +%s)
passed=0; failed=0
for t in "$@"; do
  seed_corpus=$(dirname "$(find "$src/tests/fuzz" -name "$t.cpp" | head -1)")/corpus
  bin=$(find "$build/tests/fuzz" -type f -name "$t" -perm -u+x | head -1)
  scratch=$work/corpus/$t; artifacts=$work/artifacts/$t/
  rm -rf "$scratch"; mkdir -p "$scratch" "$artifacts"
  log=$work/$t.log
  seed_arg=()
  [ -n "${CB_FUZZ_SEED:-}" ] && seed_arg=(-seed="$CB_FUZZ_SEED")
  if "$bin" -max_total_time="$secs" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
      "${seed_arg[@]}" -artifact_prefix="$artifacts" "$scratch" "$seed_corpus" >"$log" 2>&1; then
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
    cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | cut -d' ' -f2)
    ft=$(grep -o 'ft: [0-9]*' "$log" | tail -1 | cut -d' ' -f2)
    corp=$(grep -o 'corp: [0-9]*/[0-9]*[a-zA-Z]*' "$log" | tail -1 | cut -d' ' -f2)
    echo "fuzz $t: ok, seed $(sed -n 's/^INFO: Seed: //p' "$log" | head -1)," \
      "${runs:-?} inputs in $secs s, cov ${cov:-?} edges, ft ${ft:-?}," \
      "corpus ${corp:-?} (last: $(grep -E '^#[0-9]+' "$log" | tail -1 | cut -c1-110))"
    passed=$((passed + 1))
  else
    echo "fuzz $t: FAILED, seed $(sed -n 's/^INFO: Seed: //p' "$log" | head -1) (log $log," \
      "input kept in $artifacts)"
    grep -E 'ERROR|SUMMARY|runtime error|Test unit written' "$log" | head -20 || tail -20 "$log"
    failed=$((failed + 1))
  fi
done
echo "sanitized fuzzing: $passed passed, $failed failed ($(( $(date +%s) - fuzz_start )) s fuzzing," \
  "$(( $(date +%s) - start )) s in all)"
[ "$failed" -eq 0 ]
