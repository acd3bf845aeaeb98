"""The committed front-end bundle must be what js/src builds to (no stale bundle lands)."""
from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
STATIC = ROOT / "unitopia_widget" / "static"


def test_committed_bundle_matches_a_fresh_build(tmp_path):
    node = shutil.which("node")
    if node is None or not (ROOT / "js" / "node_modules" / "esbuild").exists():
        pytest.skip("needs node and `npm --prefix js ci` (esbuild) to rebuild the bundle")
    env = dict(os.environ, UNITOPIA_BUNDLE_DIR=str(tmp_path))
    subprocess.run([node, "build.mjs"], cwd=ROOT / "js", env=env, check=True, timeout=120)
    for name in ("widget.js", "widget.css", "story.js", "story-page.js"):
        fresh = (tmp_path / name).read_bytes()
        committed = (STATIC / name).read_bytes()
        assert fresh == committed, (f"unitopia_widget/static/{name} is stale: run "
                                    f"`npm --prefix js run build` and commit the result")
