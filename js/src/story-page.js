// The one-file story page (output/story_page.py): the story player over the page's
// #story-data, the arrow keys anywhere on the page.
import { mountStory } from "./story-player.js";

const data = JSON.parse(document.getElementById("story-data").textContent);
mountStory(document.getElementById("story"), data, { keys: document });
