#!/usr/bin/env bash
# Creates the venv the fracarm Python package runs in (under the build tree)
# and installs the PyPI packages Debian 12 lacks or ships too old for Dask:
# numpy, pandas, pyarrow, dask[distributed], python-control, pytest.
# Installs only what the venv does not already import, so a second run costs
# nothing and needs no network. The built extension (fracarm/_fracarm*.so)
# is found through a .pth file pointing at the build tree's package dir.
set -euo pipefail
venv=${1:?usage: setup_venv.sh VENV_DIR PACKAGE_DIR}
pkgdir=${2:?usage: setup_venv.sh VENV_DIR PACKAGE_DIR}
if [ ! -x "$venv/bin/python" ]; then
  /usr/bin/python3 -m venv "$venv"
fi
py="$venv/bin/python"
if ! "$py" -c 'import numpy, pandas, pyarrow, dask.distributed, control, pytest' 2>/dev/null; then
  "$py" -m pip install --quiet --disable-pip-version-check \
    'numpy>=1.24' 'pandas>=2.0' 'pyarrow>=14' 'dask[distributed]>=2024.1' 'control>=0.10' 'pytest>=7'
fi
site=$("$py" -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')
echo "$pkgdir" > "$site/fracarm-build.pth"
"$py" -c 'import numpy, pandas, pyarrow, dask, distributed, control, pytest; print("venv ok: numpy", numpy.__version__, "pandas", pandas.__version__, "pyarrow", pyarrow.__version__, "dask", dask.__version__, "control", control.__version__)'
# The fracarm-fleet command, in the venv's bin.
cat > "$venv/bin/fracarm-fleet" <<PYEOF
#!$venv/bin/python
import sys
from fracarm.fleet.cli import main
if __name__ == "__main__":  # Dask's worker processes re-import the main module
    sys.exit(main())
PYEOF
chmod +x "$venv/bin/fracarm-fleet"
"$py" -c 'import fracarm, fracarm.fleet; print("fracarm", fracarm.__file__)'
