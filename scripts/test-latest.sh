#!/usr/bin/env bash
# Runs the suite on the newest versions pyproject.toml allows, not on the lock: a fresh venv,
# the package and its extras with only the hand-written pins (constraints.in), then
# scripts/test.sh (arguments go to it, e.g. --quick). Run it before refreshing the lock with
# `bash scripts/lock.sh --upgrade`, and write what it found in docs/changelog.md.
set -euo pipefail
cd "$(dirname "$0")/.."
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
python -m venv "$tmp/venv"
"$tmp/venv/bin/python" -m pip install -q -c constraints.in -e ".[test,icons,bench,video,docs]"
echo "newer than the lock (package: locked -> installed):"
"$tmp/venv/bin/python" -m pip list --format=freeze | python -c '
import re, sys
lock = dict(re.findall(r"^([A-Za-z0-9_.-]+)==(\S+)", open("constraints.txt").read(), re.M))
lock = {re.sub(r"[-_.]+", "-", k).lower(): v for k, v in lock.items()}
for line in sys.stdin:
    name, _, version = line.strip().partition("==")
    key = re.sub(r"[-_.]+", "-", name).lower()
    if key in lock and lock[key] != version.split("+")[0]:
        print(f"  {name}: {lock[key]} -> {version}")'
PATH="$tmp/venv/bin:$PATH" VIRTUAL_ENV="$tmp/venv" bash scripts/test.sh "$@"
