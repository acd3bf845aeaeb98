// The story widget (jupyter/story.py): the story player over the model's "story" trait,
// its slide index and transition seconds synced both ways.
import { mountStory } from "./story-player.js";

function render({ model, el, signal }) {
  let player = null;
  function mount() {
    el.replaceChildren();
    const data = model.get("story");
    if (!data || !data.slides || !data.slides.length) return;
    player = mountStory(el, data, {
      seconds: model.get("seconds"),
      index: model.get("index"),
      onIndex: i => { model.set("index", i); model.save_changes(); },
      onSeconds: s => { model.set("seconds", s); model.save_changes(); },
    });
  }
  const onIndex = () => { if (player && player.index !== model.get("index")) player.go(model.get("index")); };
  const onSeconds = () => { if (player) player.setSeconds(model.get("seconds")); };
  model.on("change:story", mount);
  model.on("change:index", onIndex);
  model.on("change:seconds", onSeconds);
  signal?.addEventListener("abort", () => {
    model.off("change:story", mount);
    model.off("change:index", onIndex);
    model.off("change:seconds", onSeconds);
  });
  mount();
}

export default { render };
