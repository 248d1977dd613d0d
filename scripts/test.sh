#!/usr/bin/env bash
# Every test: gtest (C++ core), rostest (whole system through a real roscore) and pytest (Python
# tools). Sets the machine up first. Exits non-zero on any failure, and on any skipped test that
# scripts/summarize_junit.py does not allow (a missing dependency must fail); the last line is the summary.
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$repo/scripts/setup.sh"
# shellcheck disable=SC1091
source "$repo/scripts/env.sh"

tmp=$(mktemp -d)
export ROS_HOME="$tmp/ros_home" ROS_LOG_DIR="$tmp/ros_log"
results="$UNEXMIN_WS/build/test_results"
rm -rf "$results"
mkdir -p "$results/unexmin" "$results/pytest"

cd "$UNEXMIN_WS"
echo "[test] building tests"
catkin_make -j2 tests >"$tmp/build_tests.log" 2>&1 || { tail -n 60 "$tmp/build_tests.log"; exit 1; }
# The catkin tests (gtest, rostest: each rostest its own master on a port of its own) run beside pytest's workers:
# most of the time of either is spent waiting on start-ups. run_tests exits 0 even when a test fails: the verdict
# comes from catkin_test_results below.
# A test that hangs fails with its stack instead of holding the run: each pytest test has a time limit
# (UNEXMIN_TEST_TIMEOUT seconds, pytest-timeout), the catkin tests one for the lot (rostest's own time-limits per test).
test_timeout=${UNEXMIN_TEST_TIMEOUT:-900}
catkin_budget=${UNEXMIN_CATKIN_BUDGET:-2400}
pytest_budget=${UNEXMIN_PYTEST_BUDGET:-2400}  # [s] for all of the parallel pytest run, should a time limit itself not end a test
echo "[test] gtest + rostest (catkin_make run_tests), beside pytest"
(rc=0
  ROS_HOME="$tmp/ros_home_catkin" ROS_LOG_DIR="$tmp/ros_log_catkin" timeout --kill-after=30 "$catkin_budget" \
    catkin_make run_tests -j1 >"$tmp/run_tests.log" 2>&1 || rc=$?
  echo "$rc" >"$tmp/run_tests.rc") &
catkin_pid=$!
# pytest: files in parallel, one worker each (--dist loadfile keeps a file's module fixtures in one process);
# files with a `long` test are handed out first. The `alone` tests assert a wall-clock speed: they run after
# everything else has finished, by themselves.
workers=${UNEXMIN_TEST_WORKERS:-3}
echo "[test] pytest ($workers workers)"
set +e
# run_pytest JUNIT_NAME ARGS...: the pytest tests under the time limits above
run_pytest() {
  local junit=$1
  shift
  (cd "$repo" && timeout --kill-after=30 "$pytest_budget" python -m pytest test/pytest -q -p no:cacheprovider \
    --timeout "$test_timeout" --junitxml="$results/pytest/$junit.xml" "$@")
}
run_pytest pytest-unexmin -n "$workers" --dist loadfile -m "not alone" --durations=15
pytest_rc=$?
set -e
wait "$catkin_pid"
catkin_rc=$(cat "$tmp/run_tests.rc")
# run_tests' own exit says nothing (0 on a failed test); its time budget running out does: the tests after it never ran
if [ "$catkin_rc" -eq 124 ] || [ "$catkin_rc" -eq 137 ]; then
  echo "[test] the catkin tests ran out of their ${catkin_budget} s (UNEXMIN_CATKIN_BUDGET)" >&2
  catkin_rc=1
else
  catkin_rc=0
fi
grep -E "^\[ *(OK|FAILED|PASSED) *\]|^\[ROSTEST\]|^SUMMARY|FAILURE|ERROR" "$tmp/run_tests.log" | grep -v "^\[       OK \]" || true
echo "[test] pytest, the tests that run alone"
set +e
run_pytest pytest-unexmin-alone -m alone
alone_rc=$?
set -e
for rc in "$pytest_rc" "$alone_rc"; do
  if [ "$rc" -ne 0 ] && [ "$rc" -ne 1 ]; then
    echo "[test] pytest could not run (exit $rc)" >&2
  fi
done

echo "[test] results"
set +e
catkin_test_results --verbose "$results" >"$tmp/results.txt" 2>&1
results_rc=$?
set -e
grep -vE "^(Skipping|$)" "$tmp/results.txt" | tail -n 40
python "$repo/scripts/summarize_junit.py" "$results"
summary_rc=$?
[ "$catkin_rc" -eq 0 ] && [ "$results_rc" -eq 0 ] && [ "$pytest_rc" -eq 0 ] && [ "$alone_rc" -eq 0 ] && [ "$summary_rc" -eq 0 ]
