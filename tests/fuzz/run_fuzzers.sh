#!/usr/bin/env bash
# Builds the libFuzzer targets with Debian's clang in build-fuzz/ (SAS_FUZZ=ON: libFuzzer + ASan +
# UBSan) and runs each for a while, starting from the committed seed corpus.
#   tests/fuzz/run_fuzzers.sh [seconds per target, default 60] [target ...]
# Targets: kiosk_config material_file texture_file image_loader audio_file (default: all).
# New corpus entries go to build-fuzz/fuzz-corpus/<target> (not the committed seeds); a crash,
# leak or sanitizer report is written to build-fuzz/fuzz-artifacts/<target>/ and the script exits
# non-zero. Keep a fixed crash's input in tests/fuzz/regressions/<target>/ so CTest replays it.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
seconds="${1:-60}"
shift || true
targets=("$@")
[ "${#targets[@]}" -gt 0 ] || targets=(kiosk_config material_file texture_file image_loader audio_file)
build="$repo/build-fuzz"
jobs="${SAS_FUZZ_JOBS:-2}"

launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
cmake -S "$repo" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang \
  -DCMAKE_CXX_COMPILER=clang++ -DSAS_FUZZ=ON -DSAS_BUILD_TESTS=OFF -DSAS_BUILD_BENCH=OFF \
  "${launcher[@]}" >/dev/null
cmake --build "$build" -j"$jobs" --target "${targets[@]/#/fuzz_}"

failed=()
for target in "${targets[@]}"; do
  corpus="$build/fuzz-corpus/$target"
  artifacts="$build/fuzz-artifacts/$target"
  rm -rf "$artifacts"  # a kept crash input belongs in tests/fuzz/regressions/, not here
  mkdir -p "$corpus" "$artifacts"
  seeds=("$repo/tests/fuzz/corpus/$target")
  [ -d "$repo/tests/fuzz/regressions/$target" ] && seeds+=("$repo/tests/fuzz/regressions/$target")
  echo "== fuzz_$target for ${seconds} s"
  # -rss_limit_mb / -malloc_limit_mb: one input that makes a loader allocate more than 512 MB is a
  # finding (a few-byte file must not cost the kiosk half its memory). -timeout: 10 s per input.
  rc=0
  "$build/tests/fuzz/fuzz_$target" "$corpus" "${seeds[@]}" -max_total_time="$seconds" \
    -rss_limit_mb=1024 -malloc_limit_mb=512 -timeout=10 -max_len=65536 -print_final_stats=1 \
    -artifact_prefix="$artifacts/" > "$build/fuzz-$target.log" 2>&1 || rc=$?
  grep -E '^(#[0-9]+ *DONE|==[0-9]+==ERROR|SUMMARY|stat::number_of_executed_units|stat::peak_rss_mb|Test unit written)' \
    "$build/fuzz-$target.log" || true
  if [ "$rc" -ne 0 ] || ls "$artifacts"/* >/dev/null 2>&1; then failed+=("$target"); fi
done
if [ "${#failed[@]}" -gt 0 ]; then
  echo "FAILED (see build-fuzz/fuzz-artifacts/ and build-fuzz/fuzz-<target>.log): ${failed[*]}"
  exit 1
fi
echo "all fuzz targets ran ${seconds} s without a finding"
