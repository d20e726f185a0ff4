#!/usr/bin/env bash
# CTest fixture: a venv under the build directory with Python's cantools and
# python-can (neither packaged by Debian 12): cantools is the independent
# decoder of the rig's candump logs, python-can's candump reader
# (can.io.CanutilsLogReader) the independent reader the rig's candump grammar
# is checked against. Installs from PyPI only what the venv does not have.
set -euo pipefail
venv=${1:?usage: setup_pyvenv.sh VENV_DIR}
if [ ! -x "$venv/bin/python" ]; then
  /usr/bin/python3 -m venv "$venv" --system-site-packages
fi
if ! "$venv/bin/python" -c 'import cantools' 2>/dev/null; then
  "$venv/bin/pip" install --quiet cantools
fi
if ! "$venv/bin/python" -c 'import can.io' 2>/dev/null; then
  "$venv/bin/pip" install --quiet python-can
fi
"$venv/bin/python" -c 'import cantools, can; print("cantools", cantools.__version__, "python-can", can.__version__)'
