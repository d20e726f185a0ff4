#!/usr/bin/env bash
# CTest fixture: a venv under the build directory with Python packages that
# Debian 12 does not package: cantools (the independent decoder of the rig's
# candump logs), python-can (its candump reader can.io.CanutilsLogReader is
# the independent reader the rig's candump grammar is checked against) and
# canopen (the independent CANopen master of tests/hil/canopen_master.py).
# Installs from PyPI only what the venv lacks.
set -euo pipefail
venv=${1:?usage: setup_pyvenv.sh VENV_DIR}
if [ ! -x "$venv/bin/python" ]; then
  /usr/bin/python3 -m venv "$venv" --system-site-packages
fi
if ! "$venv/bin/python" -c 'import cantools' 2>/dev/null; then
  "$venv/bin/pip" install --quiet cantools
fi
if ! "$venv/bin/python" -c 'import canopen, can.io, can.interfaces.socketcand' 2>/dev/null; then
  "$venv/bin/pip" install --quiet 'canopen>=2.3' 'python-can>=4.3'
fi
"$venv/bin/python" -c 'import cantools, can, canopen; print("cantools", cantools.__version__, "python-can", can.__version__, "canopen", canopen.__version__)'
