"""The layer settings set count=, per=, rounding and partial (issue 50), on the fake model."""
from __future__ import annotations

import pytest

pytestmark = pytest.mark.browser


def layer(page) -> dict:
    return page.evaluate("fake.get('design').layers[0]")


def test_count_per_rounding_and_partial_are_set_from_the_layer_settings(page):
    page.evaluate("() => unitopia.mount(unitopia.defaultState(), {views: 1})")
    assert page.locator('[data-setting="rounding"]').count() == 0, "rounding shows once per is set"
    page.select_option('[data-setting="count"]', "Duration")
    page.fill('[data-setting="per"]', "100")
    page.press('[data-setting="per"]', "Enter")
    assert (layer(page)["count"], layer(page)["per"]) == ("Duration", 100)
    page.select_option('[data-setting="rounding"]', "ceil")
    page.check('[data-setting="partial"]')
    assert (layer(page)["rounding"], layer(page)["partial"]) == ("ceil", True)
    page.fill('[data-setting="per"]', "")
    page.press('[data-setting="per"]', "Enter")
    page.select_option('[data-setting="count"]', "")
    assert (layer(page)["per"], layer(page)["count"]) == (None, None)
    assert page.locator('[data-setting="partial"]').count() == 0
