#!/bin/sh
# Runs each libFuzzer target for SECONDS (after replaying its regression inputs), one at a time.
# usage: fuzz.sh BUILD_DIR SECONDS [TARGET...]   (targets: case stl checkpoint; default all)
# The working corpus grows in BUILD_DIR/corpus/TARGET; the seeds in fuzz/corpus/TARGET (plus the
# example cases and bad inputs) are only read. A crash, leak, sanitizer report or timeout leaves
# its input in BUILD_DIR/artifacts/ and makes the script fail. Each run's final line:
#   fuzz TARGET seconds=S execs=N cov=C ft=F corpus=K status=ok|FOUND
set -u
B=$1
S=$2
shift 2
TARGETS=${*:-case stl checkpoint}
cd "$(dirname "$0")/.."
status=0
for t in $TARGETS; do
    bin="$B/fuzz_$t"
    [ -x "$bin" ] || { echo "fuzz: $bin not built (make fuzz-build)" >&2; exit 1; }
    mkdir -p "$B/corpus/$t" "$B/artifacts"
    case $t in
    case) seeds="fuzz/corpus/case cases tests/bad_inputs" ;;
    stl) seeds="fuzz/corpus/stl cases/geometry tests/bad_inputs/geometry" ;;
    checkpoint) seeds="fuzz/corpus/checkpoint" ;;
    esac
    export OMP_NUM_THREADS=1
    export ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1
    export LSAN_OPTIONS=suppressions=$(pwd)/fuzz/lsan.supp
    export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
    # Regression inputs first: every past finding must stay fixed.
    if ls fuzz/regressions/$t/* >/dev/null 2>&1; then
        "$bin" -runs=1 fuzz/regressions/$t/* > "$B/regressions_$t.log" 2>&1 \
            || { echo "fuzz $t: a regression input fails again:"; tail -n 30 "$B/regressions_$t.log"; status=1; continue; }
    fi
    log="$B/fuzz_$t.log"
    # shellcheck disable=SC2086
    "$bin" -max_total_time="$S" -max_len=8192 -timeout=25 -rss_limit_mb=2048 -print_final_stats=1 \
        -dict="fuzz/$t.dict" -artifact_prefix="$B/artifacts/$t-" "$B/corpus/$t" $seeds > "$log" 2>&1
    rc=$?
    execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$')
    last=$(grep -E '^#[0-9]+' "$log" | tail -n 1)
    cov=$(printf '%s' "$last" | grep -o 'cov: [0-9]*' | grep -o '[0-9]*')
    ft=$(printf '%s' "$last" | grep -o 'ft: [0-9]*' | grep -o '[0-9]*')
    corp=$(printf '%s' "$last" | grep -o 'corp: [0-9]*' | grep -o '[0-9]*')
    if [ $rc -eq 0 ]; then st=ok; else st=FOUND; status=1; fi
    echo "fuzz $t seconds=$S execs=${execs:-?} cov=${cov:-?} ft=${ft:-?} corpus=${corp:-?} status=$st"
    if [ $rc -ne 0 ]; then
        grep -E "ERROR|SUMMARY|unclean|runtime error|artifact" "$log" | head -n 20
    fi
done
exit $status
