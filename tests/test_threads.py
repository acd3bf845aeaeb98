"""How ``import unitopia_widget`` sets PyTorch's OpenMP threads waiting
(``unitopia_widget/__init__.py``): in a notebook kernel idle threads sleep at once, in a
script they wait actively a few milliseconds for the next op, and a policy the user set is
kept. Each case imports the package in a fresh process, as the setting must precede torch."""
from __future__ import annotations

import json
import os
import subprocess
import sys

PROBE = """import json, os
{before}
import unitopia_widget
print(json.dumps({{k: os.environ.get(k) for k in ("OMP_WAIT_POLICY", "GOMP_SPINCOUNT")}}))"""


def imported(before: str = "", **env) -> dict:
    """The two variables after ``import unitopia_widget`` in a fresh process that ran
    ``before`` first, with neither set beforehand unless ``env`` sets it."""
    clean = {k: v for k, v in os.environ.items() if k not in ("OMP_WAIT_POLICY", "GOMP_SPINCOUNT")}
    done = subprocess.run([sys.executable, "-c", PROBE.format(before=before)], env={**clean, **env},
                          capture_output=True, text=True, check=True)
    return json.loads(done.stdout.splitlines()[-1])


def test_a_script_s_threads_wait_a_little_for_the_next_op():
    assert imported() == {"OMP_WAIT_POLICY": None, "GOMP_SPINCOUNT": "100000"}


def test_a_notebook_kernel_s_idle_threads_sleep_at_once():
    assert imported("import ipykernel") == {"OMP_WAIT_POLICY": "PASSIVE", "GOMP_SPINCOUNT": None}


def test_a_wait_policy_the_user_set_is_kept():
    assert imported(OMP_WAIT_POLICY="ACTIVE") == {"OMP_WAIT_POLICY": "ACTIVE", "GOMP_SPINCOUNT": None}
