#!/usr/bin/env bash
# Runs the tests on every core (pytest-xdist; a test file stays on one worker, so its module
# fixtures, the layouts its tests share, are built once, and a notebook runs in one kernel).
#   bash scripts/test.sh           every test: Python, JavaScript (node --test), browser
#                                  (Playwright + Chromium), real JupyterLab, the notebooks (nbval),
#                                  the wheel as a user installs it, and the docs (mkdocs --strict)
#   bash scripts/test.sh --quick   all but the browser, JupyterLab, notebook and corpus tests
# Further arguments go to pytest (e.g. -x, -k name, -n 0 for one process).
set -euo pipefail
cd "$(dirname "$0")/.."
export OMP_WAIT_POLICY=PASSIVE
if [ "${1:-}" = "--quick" ]; then
  shift
  exec python -m pytest tests -m "not browser and not jupyterlab and not corpus" \
    -n auto --dist loadfile -p no:cacheprovider "$@"
fi
exec python -m pytest tests notebooks --nbval-lax -n auto --dist loadfile -p no:cacheprovider "$@"
