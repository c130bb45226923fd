#!/usr/bin/env bash
# The Python package as a user installs it: a fresh virtual environment that sees Debian's numpy,
# pytest and Pillow (--system-site-packages), `pip install --no-build-isolation .` (no package
# index needed: Debian's setuptools, wheel, pybind11-dev; pyproject.toml), then tests/python
# against the installed package, run from a folder where neither the checkout nor build/python
# is on the path. The CLI-vs-module tests need the command-line tool: VSIL_BINARY (default
# build/vsil, which scripts/test.sh builds). Environment: VSIL_VENV (default build-pip/venv),
# PYTHON (default /usr/bin/python3, Debian's, for which python3-numpy is built).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
venv=${VSIL_VENV:-$root/build-pip/venv}
binary=${VSIL_BINARY:-$root/build/vsil}
[[ -x $binary ]] || { echo "test-python-package: no $binary (run scripts/test.sh first)" >&2; exit 1; }

rm -rf "$venv"
"${PYTHON:-/usr/bin/python3}" -m venv --system-site-packages "$venv"
"$venv/bin/pip" install --no-build-isolation --no-index -q "$root"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
# The installed copy, not the build tree's: vsil.__file__ must lie in the venv.
env -u PYTHONPATH "$venv/bin/python" - "$venv" <<'PY'
import os, sys
import vsil
venv = os.path.realpath(sys.argv[1])
assert os.path.realpath(vsil.__file__).startswith(venv + os.sep), vsil.__file__
print(f"test-python-package: vsil {vsil.__version__} from {vsil.__file__}")
PY
env -u PYTHONPATH VSIL_BINARY="$binary" VSIL_TEST_INSTALLED="$venv" \
  "$venv/bin/python" -m pytest -q -p no:cacheprovider "$root/tests/python"
# What pip installed, pip removes.
"$venv/bin/pip" uninstall -y -q vsil
if env -u PYTHONPATH "$venv/bin/python" -c "import vsil" 2>/dev/null; then
  echo "test-python-package: vsil is still importable after pip uninstall" >&2
  exit 1
fi
