"""Runs the front end's pure-logic unit tests (js/test/*.test.mjs) with node's test runner."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def test_node_unit_tests_pass():
    node = shutil.which("node")
    if node is None:
        pytest.skip("node is not installed: the JavaScript unit tests need Node.js 20+")
    result = subprocess.run(
        [node, "--test", "js/test/"], cwd=ROOT, capture_output=True, text=True, timeout=120
    )
    summary = "\n".join(line for line in result.stdout.splitlines() if line.startswith(("# ", "not ok")))
    assert result.returncode == 0, f"node --test js/test/ failed:\n{summary}\n{result.stderr[-2000:]}"
