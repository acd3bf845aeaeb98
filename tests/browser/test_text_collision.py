"""Text a reader can read (issue 46, part 5): a gallery of charts made from a real table is
exported to SVG, loaded in Chromium and measured with ``getBBox``: no text box crosses
another text box or a mark's box, no text lies outside the view box, and no axis line
crosses a mark. ``GALLERY`` is the list to extend: one entry per chart, laid out once."""

from __future__ import annotations

import numpy as np
import pytest

import unitopia_widget as uw

pytestmark = [pytest.mark.browser, pytest.mark.usefixtures("one_thread"),
              pytest.mark.filterwarnings("ignore:.*(dropna|missing):UserWarning")]
data = pytest.importorskip("vega_datasets", reason="the gallery draws vega_datasets' cars").data

LONG = {"USA": "United States of America", "Europe": "Europe (Germany, France, Italy, Sweden)",
        "Japan": "Japan"}


def cars(n: int = 150):
    """``n`` rows of the cars table, every origin, some horsepowers missing."""
    table = data.cars()
    table = table.iloc[np.linspace(0, len(table) - 1, n).astype(int)].reset_index(drop=True)
    table["Origin (long)"] = table["Origin"].map(LONG)
    table["Origin and cylinders"] = table["Origin (long)"] + ", " + \
        table["Cylinders"].astype(str) + " cylinders"
    return table


# (name, chart arguments, export arguments): each laid out once, exported once
GALLERY = [
    ("categorical y, numeric x",
     dict(mark="circle", size="Weight_in_lbs", color="Origin", x="Horsepower", y="Origin",
          dropna=True), dict(axes=True)),
    ("log x, numeric y, datetime colour, title and caption",
     dict(mark="circle", color="Year", x="Displacement", x_scale="log", y="Miles_per_Gallon",
          dropna=True),
     dict(axes=True, title="Displacement and mileage", caption="One mark per car, coloured by "
          "its model year; displacement on a log scale.")),
    ("long categories on x, legend on top",
     dict(mark="square", color="Origin (long)", x="Origin (long)", size="Weight_in_lbs"),
     dict(axes=True, legend="top", title="Cars by origin")),
    ("numeric colour with missing values, legend at the bottom, caption",
     dict(mark="circle", size="Weight_in_lbs", color="Horsepower"),
     dict(legend="bottom", title="Horsepower", caption="Grey marks: horsepower unknown.")),
    ("datetime colour, legend on the left",
     dict(mark="circle", size="Acceleration", color="Year"), dict(legend="left")),
    ("long category names, legend on the right, y axis of bands",
     dict(mark="circle", color="Origin (long)", y="Origin (long)", x="Acceleration"),
     dict(axes=True, legend="right")),
    ("three layers by origin sharing a numeric x and a y of bands",
     dict(mark="circle", by="Origin", color="Origin", size="Weight_in_lbs", x="Horsepower",
          y="Origin", dropna=True), dict(axes=True, legend="bottom")),
    ("piles in columns, long names, title, caption, legend at the bottom",
     dict(mark="circle", by="Origin (long)", color="Origin (long)", size="Weight_in_lbs"),
     dict(legend="bottom", title="Cars by origin", caption="One mark per car, sized by its "
          "weight; each pile's area is the total weight of its cars.")),
    ("piles in rows, long names, title, caption, legend at the bottom",
     dict(mark="circle", by="Origin (long)", color="Origin (long)", piles="rows"),
     dict(legend="bottom", title="Cars by origin", caption="One mark per car.")),
    ("piles in a grid, numeric colour with missing values, legend at the bottom",
     dict(mark="square", by="Origin (long)", color="Horsepower", piles="grid"),
     dict(legend="bottom", title="Horsepower by origin", caption="Grey: horsepower unknown.")),
    ("piles in columns, short names, legend on the right",
     dict(mark="circle", by="Origin", color="Origin", size="Weight_in_lbs"),
     dict(legend="right", title="Cars by origin", caption="Sized by weight.")),
    ("nine piles in columns, long names, legend on top",
     dict(mark="circle", by="Origin and cylinders", color="Origin"),
     dict(legend="top", title="Cars by origin and cylinders", caption="One mark per car.")),
    ("nine piles in a grid, long names, legend on the left",
     dict(mark="circle", by="Origin and cylinders", color="Origin", piles="grid"),
     dict(legend="left", caption="One mark per car.")),
]

MEASURE = """(svg) => {
    const root = svg.getCTM().inverse();
    const box = (el) => {   // the element's bounding box in the root's user units
        const b = el.getBBox(), m = root.multiply(el.getCTM());
        const pts = [[b.x, b.y], [b.x + b.width, b.y], [b.x, b.y + b.height],
                     [b.x + b.width, b.y + b.height]].map(([x, y]) => new DOMPoint(x, y).matrixTransform(m));
        const xs = pts.map((p) => p.x), ys = pts.map((p) => p.y);
        return [Math.min(...xs), Math.min(...ys), Math.max(...xs), Math.max(...ys)];
    };
    const texts = [...svg.querySelectorAll("text")].filter((t) => t.textContent.trim())
        .map((t) => ({text: t.textContent, box: box(t)}));
    const marks = [...svg.querySelectorAll("g.unit use, use.legend-mark, rect.legend-bar")]
        .map((m) => ({what: m.closest("g.unit") ? "mark " + m.closest("g.unit").dataset.row
                                                 : "legend mark", box: box(m)}));
    const lines = [...svg.querySelectorAll("g.axis line")].map((l) => {
        const m = root.multiply(l.getCTM());
        const p = (x, y) => new DOMPoint(+l.getAttribute(x), +l.getAttribute(y)).matrixTransform(m);
        const a = p("x1", "y1"), b = p("x2", "y2");
        return [a.x, a.y, b.x, b.y];
    });
    const v = svg.viewBox.baseVal;
    const piles = svg.querySelectorAll("g.pile-labels > text.pile-label").length;
    return {texts, marks, lines, piles, view: [v.x, v.y, v.x + v.width, v.y + v.height]};
}"""

SLACK = 0.5   # px: boxes that share less than this do not touch


def overlap(a, b) -> bool:
    return min(a[2], b[2]) - max(a[0], b[0]) > SLACK and min(a[3], b[3]) - max(a[1], b[1]) > SLACK


def crosses(line, box) -> bool:
    """An axis line or tick (horizontal or vertical) through the inside of ``box``."""
    x1, y1, x2, y2 = line
    if y1 == y2:
        return box[1] + SLACK < y1 < box[3] - SLACK and \
            min(max(x1, x2), box[2]) - max(min(x1, x2), box[0]) > SLACK
    if x1 == x2:
        return box[0] + SLACK < x1 < box[2] - SLACK and \
            min(max(y1, y2), box[3]) - max(min(y1, y2), box[1]) > SLACK
    return False


def problems(measured) -> list[str]:
    """What a reader would trip over in one measured chart."""
    texts, marks, view = measured["texts"], measured["marks"], measured["view"]
    out = []
    for i, t in enumerate(texts):
        if not (t["box"][0] >= view[0] - SLACK and t["box"][1] >= view[1] - SLACK
                and t["box"][2] <= view[2] + SLACK and t["box"][3] <= view[3] + SLACK):
            out.append(f"text {t['text']!r} {t['box']} outside the view {view}")
        out += [f"text {t['text']!r} crosses text {u['text']!r}" for u in texts[i + 1:]
                if overlap(t["box"], u["box"])]
        out += [f"text {t['text']!r} crosses {m['what']}" for m in marks if overlap(t["box"], m["box"])]
    for line in measured["lines"]:
        out += [f"axis line {line} crosses {m['what']}" for m in marks if crosses(line, m["box"])]
    return out


@pytest.fixture(scope="module")
def gallery():
    """``[(name, svg), ...]``: the gallery laid out and exported."""
    table, out = cars(), []
    for name, chart_args, export_args in GALLERY:
        chart = uw.Chart(table, iterations=80, seed=0, **chart_args)
        chart.layout()
        out.append((name, chart.to_svg(**export_args)))
    return out


def test_no_text_crosses_text_or_marks_and_no_axis_crosses_a_mark(browser, gallery):
    page = browser.new_page()
    try:
        page.set_content("".join(f"<div>{svg}</div>" for _, svg in gallery))
        measured = page.evaluate(f"() => [...document.querySelectorAll('body > div > svg')]"
                                 f".map({MEASURE})")
    finally:
        page.close()
    assert len(measured) == len(GALLERY)
    assert crosses((0, 5, 10, 5), (2, 0, 8, 10)) and not crosses((0, 12, 10, 12), (2, 0, 8, 10))
    found = {name: problems(m) for (name, _), m in zip(gallery, measured)}
    for (name, _), m in zip(gallery, measured):   # the checks see what they should
        assert len(m["texts"]) >= 5 and len(m["marks"]) >= 100, name
        chart_args, export_args = next(g[1:] for g in GALLERY if g[0] == name)
        assert bool(m["lines"]) == export_args.get("axes", False)
        piled = "by" in chart_args and not {"x", "y"} & set(chart_args)   # by= with x= places
        piles = cars()[chart_args["by"]].nunique() if piled else 0
        assert m["piles"] == piles, name   # each pile's label is measured
    bad = {name: p[:5] for name, p in found.items() if p}
    assert not bad, bad
