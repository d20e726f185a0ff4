#!/usr/bin/env bash
# Runs one pytest file for CTest. Fails when pytest fails, collects no test
# (pytest's exit 5) or skips one: a test that does not run cannot pass.
set -euo pipefail
py=${1:?usage: run_pytest.sh PYTHON TEST_FILE WORK_DIR}
test=${2:?}
work=${3:?}
rm -rf "$work"
mkdir -p "$work"
report="$work/junit.xml"
set +e
"$py" -m pytest -q -p no:cacheprovider -rs --basetemp="$work/tmp" --junitxml="$report" "$test"
rc=$?
set -e
if [ $rc -eq 5 ]; then
  echo "run_pytest: no tests collected in $test" >&2
  exit 1
fi
[ $rc -eq 0 ] || exit $rc
"$py" - "$report" <<'PY'
import sys, xml.etree.ElementTree as ET
s = ET.parse(sys.argv[1]).getroot()
s = s if s.tag == "testsuite" else s.find("testsuite")
n, skipped = int(s.get("tests")), int(s.get("skipped"))
if n == 0 or skipped:
    sys.exit("run_pytest: %d tests, %d skipped: every test must run" % (n, skipped))
print("run_pytest: %d tests passed" % n)
PY
