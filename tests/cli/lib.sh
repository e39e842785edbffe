# Shared by the command-line tests (sourced): a temporary folder $T removed at exit, counters, and
#   expect CODE PATTERN command...       exit code and a grep pattern in stdout+stderr
#   expect_text CODE TEXT command...     the same with a fixed string
#   finish                               prints the counts; fails when something failed
T=$(mktemp -d /tmp/ryushi_cli_XXXXXX)
trap 'rm -rf "$T"' EXIT
pass=0
fail=0
ok() { pass=$((pass + 1)); }
bad() { echo "FAIL: $*"; fail=$((fail + 1)); }

expect_with() {
    flags=$1; code=$2; pat=$3; shift 3
    out=$("$@" 2>&1); rc=$?
    if [ "$rc" -ne "$code" ]; then bad "'$*' exited $rc, expected $code: $out"; return; fi
    if ! printf '%s' "$out" | grep -q $flags -- "$pat"; then bad "'$*': no '$pat' in: $out"; return; fi
    ok
}
expect() { expect_with -G "$@"; }
expect_text() { expect_with -F "$@"; }

finish() {
    echo "$pass passed, $fail failed"
    [ $fail -eq 0 ]
}
