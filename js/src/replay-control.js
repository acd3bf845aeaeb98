// The replay control in the top bar: a play / pause button (data-action="replay") and a
// scrub slider over the last run's frames (replay.js); data-state on [data-role="replay"]
// is "live", "playing" or "paused".
import { h } from "./dom.js";
import { Player, Recording } from "./replay.js";

/**
 * The replay control: a play / pause button and a scrub slider (both native controls, so
 * Tab, Space, Enter, the arrow keys, Home and End work). It shows once a run left two
 * frames or more. `onChange()` after every move asks the view to repaint the marks.
 */
export function createReplay(onChange) {
  const recording = new Recording();
  const player = new Player(recording);
  const button = h("button", {
    type: "button", class: "ut-btn", dataset: { action: "replay" },
    onclick: () => {
      if (player.playing) player.pause();
      else player.play(performance.now());
      show();
    },
  });
  const slider = h("input", {
    type: "range", class: "ut-replay-scrub", min: "0", max: "0", step: "1", value: "0",
    title: "Replay position (frame of the last run)", "aria-label": "Replay position (frame of the last run)",
    oninput: () => {
      player.seek(Number(slider.value));
      show();
    },
  });
  const el = h("div", { class: "ut-group ut-replay", dataset: { role: "replay", state: "live" }, role: "group", "aria-label": "Replay of the last run", hidden: true }, button, slider);

  /** The button, slider and state follow the player. */
  function sync() {
    const label = player.playing ? "Pause the replay" : "Replay the last run's settling";
    button.textContent = player.playing ? "\u275a\u275a" : "\u25b6";
    button.title = label;
    button.setAttribute("aria-label", label);
    el.dataset.state = player.playing ? "playing" : player.position === null ? "live" : "paused";
    slider.max = String(player.end);
    slider.value = String(player.position === null ? player.end : Math.round(player.position));
  }
  const show = () => (sync(), onChange());
  sync();

  return {
    el,
    /** A frame streamed during a run. */
    record(frame) {
      recording.push(frame);
      el.hidden = recording.length < 2;
      slider.max = String(player.end);
      if (player.position === null) slider.value = slider.max;
    },
    /** A new run: the recording and the replay on screen go. */
    clear() {
      recording.clear();
      player.stop();
      el.hidden = true;
      show();
    },
    /** `live`: a run streams now (a kernel is there); the replay waits until it ends. */
    update(live) {
      button.disabled = slider.disabled = !!live;
      if (live && player.position !== null) player.stop(), show();
    },
    /** Called by the view's paint at time `now`; true when the frame on screen moved. */
    step(now) {
      const moved = player.step(now);
      if (moved) sync();
      return moved;
    },
    frame: () => player.frame(),
    /** The received frame index on screen, or null while the live frames show. */
    position: () => player.position,
    playing: () => player.playing,
  };
}
