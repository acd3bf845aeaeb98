"""Tests for the command line (unitopia_widget.__main__): ``explain`` on a small design."""
import numpy as np
import pandas as pd
import pytest

import unitopia_widget as uw
from unitopia_widget.__main__ import main

pytestmark = pytest.mark.usefixtures("one_thread")


def test_explain_prints_the_iterations_of_each_phase_and_rule(tmp_path, capsys):
    df = pd.DataFrame({"v": np.random.default_rng(0).uniform(1, 5, 30)})
    chart = uw.Chart(df, mark="circle", size="v", container=uw.Container.ellipse(400, 250, 200, 200),
                     boundary="closed", iterations=150)
    chart.save(tmp_path / "design.json")
    df.to_csv(tmp_path / "rows.csv", index=False)
    assert main(["explain", str(tmp_path / "design.json"), "--data", str(tmp_path / "rows.csv")]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert "30 marks, 150 iterations" in lines[0]
    assert lines[-1].startswith("not applying: ")
    idle = lines[-1].removeprefix("not applying: ").split(", ")
    assert "pour" in idle and "resurface" in idle and "contacts" in idle   # no stage, stack or ring
    counts = {line.split()[0]: int(line.split()[1]) for line in lines[1:-1]}
    assert counts["settle"] + counts["polish"] == 150
    assert counts["best-loss"] == counts["settle"] and counts["decay"] == counts["polish"]
    assert counts["start-polish"] == 1 and counts["fill-scale"] > 0 and "pour" not in counts
    assert [line.split()[0] for line in lines[1:-1] if not line.startswith(" ")] == \
        ["settle", "polish", "finish"]


def test_explain_needs_the_data(tmp_path):
    with pytest.raises(SystemExit):
        main(["explain", str(tmp_path / "design.json")])
