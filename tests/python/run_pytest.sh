#!/usr/bin/env bash
# run_pytest.sh PYTHON MODULE_DIR VDG_TOOL [PYTEST ARGS...]
# Runs the `import vdg` tests (tests/python) with PYTHON (Debian's /usr/bin/python3: the module is
# built for it) and PYTHONPATH=MODULE_DIR; VDG_TOOL is the vdg tool the parity tests compare with.
# Exit 77 (skip) when pytest, numpy or the module cannot be imported, unless VDG_REQUIRE_PYTHON=1.
set -euo pipefail
python=$1 module_dir=$2 tool=$3
shift 3
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
skip() {
  if [[ "${VDG_REQUIRE_PYTHON:-0}" == 1 ]]; then
    echo "$1, and VDG_REQUIRE_PYTHON=1 (scripts/install-deps installs python3-pytest and python3-numpy)" >&2
    exit 1
  fi
  echo "$1: skipped" >&2
  exit 77
}
[[ -x "$python" ]] || skip "$python is not there"
"$python" -c "import pytest, numpy" 2>/dev/null || skip "$python cannot import pytest and numpy"
PYTHONPATH="$module_dir" "$python" -c "import vdg" 2>/dev/null || skip "$python cannot import vdg from $module_dir"
# -p no:cacheprovider: no .pytest_cache in the source tree.
export PYTHONPATH="$module_dir" VDG_TOOL="$tool"
export PYTHONDONTWRITEBYTECODE=1
exec "$python" -m pytest -q -p no:cacheprovider "$here" "$@"
