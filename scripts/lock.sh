#!/usr/bin/env bash
# Recompiles constraints.txt, the lock: every package the extras below install, transitive
# ones included, at one version each, for the active Python (CI: 3.11 on Linux x86-64).
# `bash scripts/lock.sh --upgrade` takes the newest versions pyproject.toml allows; without
# it, the versions already locked stay where they still fit. Run scripts/test-latest.sh
# first: it tests the newest versions.
set -euo pipefail
cd "$(dirname "$0")/.."
EXTRAS=(--extra test --extra icons --extra bench --extra video --extra docs)
# torch==2.13.0 (constraints.in) resolves to the local CPU wheel in /opt/wheels, whose
# metadata lists no nvidia-* packages; PyPI's 2.13.0 would list them.
# The lock keeps the versions it holds, read from constraints.txt; its torch line lost the
# local label below, and read so it would be PyPI's CUDA build: give the label back first.
[ -f constraints.txt ] && sed -i -E 's/^torch==([0-9.]+)$/torch==\1+cpu/' constraints.txt
uv pip compile pyproject.toml "${EXTRAS[@]}" -c constraints.in \
  --python "$(command -v python)" \
  --find-links /opt/wheels --no-emit-find-links --custom-compile-command "bash scripts/lock.sh" \
  -o constraints.txt -q "$@"
# The local label (+cpu) is dropped: torch==2.13.0 still takes the local CPU wheel where
# pip's find-links offers it, and PyPI's torch 2.13.0 elsewhere.
sed -i -E 's/^(torch==[^+ ]+)\+[a-z0-9.]+/\1/' constraints.txt
if grep -q '^nvidia-' constraints.txt; then
  echo "lock.sh: the lock pulls nvidia-* packages: check the torch pin in constraints.in" >&2; exit 1
fi
echo "constraints.txt: $(grep -c '==' constraints.txt) pins"
