#!/usr/bin/env bash
# run_golden.sh SCULPT scripts/case.bsp: runs the script from the repository root and compares
# stdout+stderr with scripts/case.expect (options from scripts/case.args when it exists); the
# exit code must be 1 under scripts/errors/, else 0.
set -u
sculpt=$1 script=$2
expect=${script%.bsp}.expect
# scripts/case.args, if present, holds command-line options for the run (-D name=value ...).
args=()
if [ -f "${script%.bsp}.args" ]; then read -r -a args < "${script%.bsp}.args"; fi
actual=$("$sculpt" "${args[@]}" "$script" 2>&1)
status=$?
want=0
case $script in scripts/errors/*) want=1 ;; esac
if [ "$status" != "$want" ]; then
  echo "exit status $status, expected $want"
  echo "$actual"
  exit 1
fi
if ! diff -u "$expect" <(printf '%s\n' "$actual"); then
  echo "output differs from $expect"
  exit 1
fi
