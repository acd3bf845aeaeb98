#!/usr/bin/env bash
# Installs everything the package and its tests need on a fresh machine (Debian, Python 3.10+, Node 20+).
set -euo pipefail
cd "$(dirname "$0")/.."
if [ ! -x /usr/bin/chromium ]; then   # the browser tests drive Debian's Chromium
  if [ "$(id -u)" = 0 ]; then apt-get update -q && apt-get install -y -q chromium; \
  else sudo apt-get update -q && sudo apt-get install -y -q chromium; fi
fi
# constraints.txt is the lock (scripts/lock.sh): every package below at the version the suite
# passes with, so every machine tests the same versions. The package itself keeps broad ranges.
# python -m pip: the interpreter (or venv) that is active.
python -m pip install -q -c constraints.txt -e ".[test,icons,bench,video,docs]"
npm --prefix js ci --no-audit --no-fund
