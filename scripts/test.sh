#!/usr/bin/env bash
# Runs every test: Python, JavaScript (node --test), browser (Playwright + Chromium),
# real JupyterLab end-to-end, and the notebooks (nbval).
set -euo pipefail
cd "$(dirname "$0")/.."
export OMP_WAIT_POLICY=PASSIVE
python -m pytest tests notebooks --nbval-lax -p no:cacheprovider "$@"
