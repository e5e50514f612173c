# The shared part of the command-line tests (sourced, not run): each test sets RADRECON (the
# binary), TMP (its scratch folder) and RADRECON_COMMAND (an array: the subcommand every `run`
# prefixes, empty for none), then uses these checks and ends with `finish NAME`.
# Outputs of a run NAME are kept in $TMP/NAME.stdout, .stderr and .rc.

failures=0
fail() {
  echo "FAIL: $*" >&2
  failures=$((failures + 1))
}

# run NAME ARGS...: runs `radrecon ${RADRECON_COMMAND[@]} ARGS`, capturing its outputs.
run() {
  local name=$1
  shift
  "$RADRECON" "${RADRECON_COMMAND[@]}" "$@" >"$TMP/$name.stdout" 2>"$TMP/$name.stderr"
  echo $? >"$TMP/$name.rc"
}
rc() { cat "$TMP/$1.rc"; }

expect_rc() {  # NAME CODE; returns 1 when it fails
  local got
  got=$(rc "$1")
  if [ "$got" != "$2" ]; then
    fail "$1: exit code $got, expected $2; stderr: $(head -c 500 "$TMP/$1.stderr")"
    return 1
  fi
}
expect_nonzero() {  # NAME
  if [ "$(rc "$1")" = 0 ]; then fail "$1: exit code 0, expected non-zero"; fi
}
expect_stderr_has() {  # NAME TEXT
  if ! grep -qF -- "$2" "$TMP/$1.stderr"; then
    fail "$1: stderr does not mention '$2'; stderr: $(head -c 500 "$TMP/$1.stderr")"
  fi
}
expect_stderr_lacks() {  # NAME TEXT
  if grep -qF -- "$2" "$TMP/$1.stderr"; then
    fail "$1: stderr mentions '$2'; stderr: $(head -c 500 "$TMP/$1.stderr")"
  fi
}
expect_stderr_nonempty() {  # NAME
  if [ ! -s "$TMP/$1.stderr" ]; then fail "$1: no message on stderr"; fi
}
expect_no_output() {  # NAME PATH: neither the file nor a temporary sibling of it exists
  local base
  base=$(basename "$2")
  if compgen -G "$(dirname "$2")/$base*" >/dev/null; then
    fail "$1: output left behind: $(ls "$(dirname "$2")/$base"*)"
  fi
}

refuse() {  # NAME TEXT OUT ARGS...: run with --out OUT --quiet; expects exit 2, TEXT on stderr and no OUT
  local name=$1 text=$2 out=$3
  shift 3
  run "$name" "$@" --out "$out" --quiet
  expect_rc "$name" 2
  expect_stderr_has "$name" "$text"
  expect_no_output "$name" "$out"
}

finish() {  # NAME: the verdict and the exit code
  if [ "$failures" -ne 0 ]; then
    echo "$1: $failures failure(s)" >&2
    exit 1
  fi
  echo "$1: all checks passed"
}
