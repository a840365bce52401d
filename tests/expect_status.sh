#!/bin/sh
# expect_status.sh STATUS COMMAND [ARG...]: runs the command, its stderr with its stdout, and says so
# when it exits with another status than STATUS. CTest takes a test that matches its
# PASS_REGULAR_EXPRESSION as passed whatever its exit status; the tests that use this name the line
# below in their FAIL_REGULAR_EXPRESSION, so the status is checked too.
expected=$1
shift
case $expected in
  '' | *[!0-9]*)
    echo "unexpected exit status: STATUS '$expected' is not a number"
    exit 1
    ;;
esac
"$@" 2>&1
status=$?
if [ "$status" -ne "$expected" ]; then
  echo "unexpected exit status $status (expected $expected)"
  exit 1
fi
exit 0
