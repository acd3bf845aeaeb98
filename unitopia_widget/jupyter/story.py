"""``StoryWidget``: a story in the notebook, its slides and transitions played in the
browser with no kernel (``static/story.js``; traits in ``docs/protocol.md``)."""
from __future__ import annotations

import pathlib

import anywidget
import traitlets as t

STATIC = pathlib.Path(__file__).parent.parent / "static"


class StoryWidget(anywidget.AnyWidget):
    """The player of ``story`` (a ``uw.Story``): previous / next, the arrow keys when it
    has the focus, and a transition-speed slider. Shown by leaving the story last in a cell."""

    _esm = STATIC / "story.js"

    story = t.Dict().tag(sync=True)     #: Story.player(): slides, their units and the transitions
    index = t.Int(0).tag(sync=True)     #: the slide shown (0-based)
    seconds = t.Float(1.0).tag(sync=True)   #: length of a transition, s

    def __init__(self, story):
        story.run()
        super().__init__(story=story.player())
        self._story = story
        self.seconds = story.seconds

    @t.validate("index")
    def _check_index(self, proposal):
        value = proposal["value"]
        if not 0 <= value < len(self.story["slides"]):
            raise t.TraitError(f"index must be a slide number in [0, {len(self.story['slides'])}), "
                               f"got {value}")
        return value

    @t.observe("seconds")
    def _keep_seconds(self, change):
        self._story.seconds = change["new"]
