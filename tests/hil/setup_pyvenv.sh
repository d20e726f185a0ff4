#!/usr/bin/env bash
# CTest fixture: a venv under the build directory with Python's cantools (not
# packaged by Debian 12), the independent decoder of the rig's candump logs.
# Installs from PyPI only when the venv does not already have it.
set -euo pipefail
venv=${1:?usage: setup_pyvenv.sh VENV_DIR}
if [ ! -x "$venv/bin/python" ]; then
  /usr/bin/python3 -m venv "$venv" --system-site-packages
fi
if ! "$venv/bin/python" -c 'import cantools' 2>/dev/null; then
  "$venv/bin/pip" install --quiet cantools
fi
"$venv/bin/python" -c 'import cantools; print("cantools", cantools.__version__)'
