"""The story widget (static/story.js) on a fake model: previous / next and the speed slider
save the slide index and transition seconds, and an index pushed from Python moves the units."""
from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
import torch

import unitopia_widget as uw

pytestmark = pytest.mark.browser


def test_story_widget_buttons_speed_and_index_from_python(page, page_url):
    torch.set_num_threads(1)
    df = pd.DataFrame({"v": np.linspace(1, 3, 6), "k": list("ab") * 3})
    look = dict(size="v", color="k", iterations=20, canvas=(160, 100))
    story = uw.Story([uw.Chart(df, **look), uw.Chart(df, by="k", mark="star", **look)],
                     seconds=0.3).run()
    page.goto(page_url.replace("index.html", "story.html"))
    page.wait_for_function("window.unitopiaReady === true")
    data = story.player()   # markup the sanitiser would never let through: the player drops it too
    data["slides"][0]["svg"] = data["slides"][0]["svg"].replace(
        "</svg>", '<script>alert(1)</script><image href="javascript:alert(2)" onload="alert(3)" '
                  'width="9" height="9"/><a href="javascript:alert(4)"><text>x</text></a></svg>')
    page.evaluate("s => window.mountStory(s)", {"story": data, "index": 0, "seconds": 0.3})
    leftovers = page.evaluate("() => [...document.querySelectorAll('#app .story-layer')].map(h => "
                              "h.shadowRoot.querySelectorAll('script, [onload], [href^=javascript]').length)")
    assert leftovers == [0] * 4
    units = "() => [...document.querySelectorAll('#app .story-units')].filter(h => h.style.display !== 'none')" \
            ".map(h => h.shadowRoot.querySelectorAll('.story-root > g.unit').length)"
    assert page.evaluate(units) == [6]
    assert page.text_content("#app .story-count") == "1 / 2"
    page.click("#app .story-next")
    page.wait_for_function("document.querySelector('#app').dataset.moving === '0' && "
                           "document.querySelector('#app').dataset.slide === '1'")
    assert page.evaluate("window.storyModel.saves.at(-1).index") == 1
    assert page.is_disabled("#app .story-next") and page.text_content("#app .story-count") == "2 / 2"
    page.fill("#app .story-speed", "2.5")
    page.dispatch_event("#app .story-speed", "input")
    assert page.evaluate("window.storyModel.saves.at(-1).seconds") == 2.5
    page.evaluate("window.storyModel.push('seconds', 0.2); window.storyModel.push('index', 0)")
    assert page.evaluate("document.querySelector('#app').dataset.moving") == "1"
    page.wait_for_function("document.querySelector('#app').dataset.moving === '0'")
    assert page.evaluate("document.querySelector('#app').dataset.slide") == "0"
    assert page.input_value("#app .story-speed") == "0.2"
