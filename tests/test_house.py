"""The house the package keeps (docs/engine-map.md): stages that import one way, small
modules, a schedule of rules that each own a module, their settings and the state they
touch."""
from __future__ import annotations

import ast
import dataclasses
import pathlib

import unitopia_widget
from unitopia_widget.layout.rules import PHASES, SCHEDULE, State

PACKAGE = pathlib.Path(unitopia_widget.__file__).parent
LAYOUT_STAGES = ("step", "prepare", "rules")   # each imports only those before it


def imports_of(path: pathlib.Path) -> set:
    """The modules ``path`` imports, as dotted names relative to the package
    (``layout.step.raster``), absolute ``unitopia_widget`` ones included."""
    here = path.relative_to(PACKAGE).with_suffix("").parts[:-1]
    out = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom):
            if node.level:
                base = list(here[:len(here) - node.level + 1])
                name = ".".join(base + ([node.module] if node.module else []))
            elif (node.module or "").startswith("unitopia_widget"):
                name = node.module.removeprefix("unitopia_widget").lstrip(".")
            else:
                continue
            out.add(name)
            out.update(f"{name}.{alias.name}" for alias in node.names)
        elif isinstance(node, ast.Import):
            out.update(a.name.removeprefix("unitopia_widget").lstrip(".") for a in node.names
                       if a.name.startswith("unitopia_widget"))
    return out


def modules(folder: str):
    return sorted((PACKAGE / folder).rglob("*.py"))


def test_no_module_of_the_layout_engine_is_over_400_lines_and_the_solver_under_200():
    long = {str(p.relative_to(PACKAGE)): n for p in modules("layout")
            if (n := len(p.read_text().splitlines())) > 400}
    assert long == {}
    assert len((PACKAGE / "layout" / "solver.py").read_text().splitlines()) < 200


def test_the_layout_stages_import_one_way():
    for i, stage in enumerate(LAYOUT_STAGES):
        later = LAYOUT_STAGES[i + 1:] + ("solver", "engine", "frames")
        for path in modules(f"layout/{stage}"):
            wrong = {name for name in imports_of(path)
                     if any(name == f"layout.{x}" or name.startswith(f"layout.{x}.") for x in later)}
            assert not wrong, f"{path.relative_to(PACKAGE)} imports {sorted(wrong)}"


def test_each_rule_is_its_own_module_with_its_settings_and_the_state_it_touches():
    fields = {f.name for f in dataclasses.fields(State)}
    names = [rule.name for rule in SCHEDULE]
    assert len(set(names)) == len(names)
    homes = [type(rule).__module__ for rule in SCHEDULE]
    assert len(set(homes)) == len(homes)                      # one module per rule
    for rule in SCHEDULE:
        assert rule.phase in PHASES, rule.name
        assert dataclasses.is_dataclass(rule.settings), rule.name
        assert type(rule.settings).__module__ == type(rule).__module__, rule.name
        assert rule.reads and rule.writes, rule.name
        assert set(rule.reads) | set(rule.writes) <= fields, (rule.name, set(rule.reads + rule.writes) - fields)
    # the schedule runs its phases in order: settle, then polish, then the finish
    order = [PHASES.index(rule.phase) for rule in SCHEDULE]
    assert order == sorted(order)


def test_the_problem_holds_data_and_no_tuning_number():
    from unitopia_widget.layout.prepare.problem import Problem
    tuning = {"lr", "patience", "grow_overlap", "final_overlap", "room_target", "settle_motion",
              "polish_iterations", "force_weight", "legalize_rounds", "stage_wait"}
    assert not tuning & {f.name for f in dataclasses.fields(Problem)}


def test_the_package_stages_import_one_way():
    stages = ("io", "design", "layout", "output", "jupyter")
    for i, stage in enumerate(stages):
        later = stages[i + 1:] + (("chart", "hand", "story") if stage != "jupyter" else ())
        for path in modules(stage):
            wrong = {name for name in imports_of(path) if name.split(".")[0] in later}
            assert not wrong, f"{path.relative_to(PACKAGE)} imports {sorted(wrong)}"


def test_output_imports_nothing_of_the_layout_and_reads_no_private_field_of_a_chart():
    for path in modules("output"):
        name = str(path.relative_to(PACKAGE))
        assert not any(n == "layout" or n.startswith("layout.") for n in imports_of(path)), name
        tree = ast.parse(path.read_text())
        private = [node.attr for node in ast.walk(tree) if isinstance(node, ast.Attribute)
                   and node.attr.startswith("_") and not node.attr.startswith("__")
                   and isinstance(node.value, ast.Name) and "chart" in node.value.id]
        private += [node.args[1].value for node in ast.walk(tree)
                    if isinstance(node, ast.Call) and getattr(node.func, "id", "") == "getattr"
                    and len(node.args) > 1 and isinstance(node.args[1], ast.Constant)
                    and str(node.args[1].value).startswith("_")]
        assert not private, (name, private)
