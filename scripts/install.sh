#!/usr/bin/env bash
# Installs everything the package and its tests need on a fresh machine (Debian, Python 3.10+, Node 20+).
set -euo pipefail
cd "$(dirname "$0")/.."
if [ ! -x /usr/bin/chromium ]; then   # the browser tests drive Debian's Chromium
  if [ "$(id -u)" = 0 ]; then apt-get update -q && apt-get install -y -q chromium; \
  else sudo apt-get update -q && sudo apt-get install -y -q chromium; fi
fi
# constraints.txt pins torch to the CPU wheel these machines carry; the package itself accepts torch>=2.2
python -m pip install -q -c constraints.txt -e ".[test,icons,bench,video]"
npm --prefix js ci --no-audit --no-fund
