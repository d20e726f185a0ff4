#!/usr/bin/env bash
# run_pytest.sh must fail for a file without tests (pytest's exit 5), for a
# skipped test and for a failing test, and pass a passing one.
set -euo pipefail
py=${1:?usage: test_run_pytest.sh PYTHON WORK_DIR}
work=${2:?}
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$work"; mkdir -p "$work"
printf 'X = 1\n' > "$work/test_empty.py"
printf 'import pytest\n\n\n@pytest.mark.skip(reason="x")\ndef test_skipped():\n    pass\n\n\ndef test_ok():\n    pass\n' > "$work/test_skip.py"
printf 'def test_fail():\n    assert 1 == 2\n' > "$work/test_fail.py"
printf 'def test_ok():\n    assert 1 == 1\n' > "$work/test_ok.py"
for f in empty skip fail; do
  if bash "$here/run_pytest.sh" "$py" "$work/test_$f.py" "$work/run_$f" > "$work/$f.log" 2>&1; then
    echo "test_run_pytest: run_pytest.sh passed test_$f.py" >&2; cat "$work/$f.log" >&2; exit 1
  fi
done
grep -q "no tests collected" "$work/empty.log"
grep -q "every test must run" "$work/skip.log"
bash "$here/run_pytest.sh" "$py" "$work/test_ok.py" "$work/run_ok"
echo "test_run_pytest: ok"
