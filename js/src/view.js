// One rendering of the widget: builds the DOM, redraws on every trait change, and
// animates frames. All persistent state is in the model (and the per-model session).
import { h, listen } from "./dom.js";
import { commit, currentLayer, list, onModel, readDesign, redo, session, setUi, undo } from "./model-sync.js";
import { createStage } from "./stage.js";
import { ImageCache } from "./images.js";
import { MarkBitmaps } from "./bitmaps.js";
import { FrameInterpolator, decodeFloat32, decodeUint8, sameFrame } from "./frames.js";
import { HitIndex } from "./hit-index.js";
import { drawScene } from "./draw-scene.js";
import { drawOverlay } from "./draw-overlay.js";
import { MarksPainter } from "./marks-painter.js";
import { makeTools } from "./tools/index.js";
import { attachInput } from "./pointer.js";
import { createToolbar } from "./toolbar.js";
import { createStatus } from "./panels/status.js";
import { createLayersPanel } from "./panels/layers.js";
import { createSettingsPanel } from "./panels/settings.js";
import { createFieldsPanel } from "./panels/fields.js";
import { createMarkPanel } from "./panels/mark.js";
import { createLegend } from "./legend-view.js";
import { createPileLabels } from "./pile-labels.js";
import { createAxes } from "./axes-view.js";
import { copyText, download } from "./export.js";
import { createPageText, createToggles, foldPanels, guidesVisible } from "./workspace.js";
import { createReplay } from "./replay-control.js";

export function renderView({ model, el, signal }) {
  const s = session(model);
  const stage = createStage(signal);
  // data-lm-suppress-shortcuts: JupyterLab leaves keys pressed in the widget alone
  // (so Delete, Backspace and Ctrl+Z edit the sketch, not the notebook).
  const root = h("div", { class: "unitopia", dataset: { unitopia: "", status: "idle", frames: "0", lmSuppressShortcuts: "true" }, tabindex: "0" });
  const stats = { paints: 0, paintMs: 0, framesReceived: 0 };
  root.unitopiaStats = stats; // read by benchmarks/frontend_fps.py
  const hitCtx = document.createElement("canvas").getContext("2d");
  const interp = new FrameInterpolator();
  const images = new ImageCache(() => redraw("scene"));
  const bitmaps = new MarkBitmaps(() => redraw("marks"));
  let units = null, colors = null, clips = null, selected = new Set(), draft = null, index = null, indexAt = null, pinned = [];
  const dirty = new Set();
  const painter = new MarksPainter(stage.canvases.marks);
  let marksPending = false; // marks changed while a paint was still going
  let raf = 0;

  const view = {
    model, session: s, stage, root, signal,
    design: () => draft || readDesign(model),
    layer: () => currentLayer(model),
    unit: () => 1 / stage.scale,
    hitContext: () => hitCtx,
    eraserWidth: () => toolbar.eraserWidth(),
    /** Commits `next`; `before`: the design an undo returns to (default: the model's). */
    commit(next, before) {
      draft = null;
      commit(model, next, before);
    },
    setDraft(d) {
      draft = d;
      redraw("scene", "over");
    },
    setLayer: (i) => setUi(model, { layer: i, picked: null }),
    setTool: (name) => setUi(model, { tool: name, picked: null }),
    pick: (picked) => setUi(model, { picked }),
    undo: () => undo(model),
    redo: () => redo(model),
    hasFrame: () => !!interp.to,
    /** The shown layout: Float32Array (N, 4) x, y, angle, scale (null before a run). */
    frame: () => interp.to,
    units: () => units,
    selected: () => selected,
    hit: (p) => hitIndex().query(p[0], p[1]),
    marksInPolygon: (pts) => hitIndex().inPolygon(pts),
    toggleSelect(indices, additive) {
      const next = new Set(additive ? selected : []);
      for (const i of indices) additive && next.has(i) && indices.length === 1 ? next.delete(i) : next.add(i);
      model.set("selected_units", [...next].sort((a, b) => a - b));
      model.save_changes();
    },
    /** Run pressed: sent to the kernel, with a notice if nothing answers. */
    run: () => status.run(),
    /** Sends a message to the kernel; false (shown in the notice) when there is none. */
    send: (msg) => status.send(msg),
    kernel: () => status.kernel(),
    redraw,
  };

  function hitIndex() {
    const at = replay.position(); // hover and clicks hit the marks where the replay shows them
    const frame = at === null ? interp.to : replay.frame();
    if (!index || index.units !== units || index.frame !== frame || indexAt !== at) index = new HitIndex(units, frame);
    indexAt = at;
    return index;
  }

  const toolbar = createToolbar(view);
  const status = createStatus(model, signal, () => onStatus());
  const panels = [createLayersPanel(view), createSettingsPanel(view), createFieldsPanel(view), createMarkPanel(view)];
  const tools = makeTools(view);
  const legend = createLegend(view, signal);
  const pileLabels = createPileLabels(stage);
  const axes = createAxes(model, stage);
  const drawAxes = () => (axes.update(readDesign(model).canvas || [1, 1]), axes.place(), redraw("scene"));
  const drawLabels = () => pileLabels.update(list(model, "pile_labels"), readDesign(model).canvas || [1, 1]);
  const pageText = createPageText(stage.wrap);
  const side = h("div", { class: "ut-side" }, panels.map((p) => p.el));
  foldPanels(panels);
  const toggles = createToggles(side, () => redraw("over"));
  const replay = createReplay(() => redraw("marks"));
  root.append(
    h("div", { class: "ut-top" }, toolbar.el, legend.toggle, toggles.panels, toggles.guide, replay.el, status.el),
    status.banner,
    status.notice,
    h("div", { class: "ut-main" }, legend.area, side),
  );
  el.append(root);
  signal.addEventListener("abort", () => {
    cancelAnimationFrame(raf);
    bitmaps.dispose();
    root.remove();
  }, { once: true });

  function redraw(...what) {
    for (const w of what) dirty.add(w);
    if (!raf) raf = requestAnimationFrame(paint);
  }

  function paint(now) {
    raf = 0;
    if (signal.aborted) return;
    const design = view.design();
    if (stage.layout(design.canvas)) {
      ["scene", "over", "marks"].forEach((w) => dirty.add(w));
      painter.cancel();
      legend.place();
      axes.place();
    }
    if (interp.step(now)) dirty.add("marks");
    if (replay.step(now)) dirty.add("marks");
    const unit = view.unit();
    if (dirty.has("scene")) drawScene(stage.begin("scene"), stage, design, view.layer(), images);
    if (dirty.has("over")) {
      const guides = guidesVisible({ tool: s.tool, hasFrame: view.hasFrame(), shown: toggles.guidesShown() });
      drawOverlay(stage.begin("over"), { design, current: view.layer(), picked: s.picked, unit, tool: tools[s.tool], guides, pins: { list: pinned, frame: interp.to } });
    }
    if (dirty.has("marks")) marksPending = true;
    if (marksPending && !painter.busy) {
      painter.start(stage.k(), { units, frame: replay.frame() || interp.current, colors, clips, bitmaps, selected });
      marksPending = false;
    }
    if (painter.busy) {
      const t0 = performance.now();
      if (painter.step()) {
        bitmaps.need(painter.px);
        stats.paints++;
      }
      stats.paintMs += performance.now() - t0;
    }
    dirty.clear();
    if (!interp.settled || painter.busy || marksPending || replay.playing()) raf = requestAnimationFrame(paint);
  }

  // --- trait -> view -----------------------------------------------------------
  function onDesign() {
    const design = readDesign(model);
    const bg = design.background && design.background.image;
    if (typeof bg === "string" && bg.startsWith("data:image/")) {
      if (stage.bg.getAttribute("src") !== bg) stage.bg.src = bg;
      stage.bg.hidden = false;
    } else stage.bg.hidden = true;
    images.prune(new Set(design.layers.map((l) => l.container && l.container.image).filter(Boolean)));
    pageText.update(design);
    drawLabels();
    drawAxes();
    updatePanels();
    legend.place();
    redraw("scene", "over");
  }
  function updatePanels() {
    toolbar.update();
    panels.forEach((p) => p.update());
  }
  function onFrame() {
    const frame = decodeFloat32(model.get("frame"));
    stats.framesReceived++;
    if (interp.to && sameFrame(frame, interp.to)) return; // nothing moved: nothing to repaint
    const had = view.hasFrame();
    interp.push(frame, performance.now());
    if (model.get("status") === "running") replay.record(frame);
    if (model.get("status") !== "running") interp.snap();
    redraw(...(had === view.hasFrame() && !pinned.length ? ["marks"] : ["marks", "over"])); // the guides hide once marks show; pins follow
  }
  function onUnits() {
    units = decodeFloat32(model.get("units"));
    colors = decodeUint8(model.get("colors"));
    clips = decodeFloat32(model.get("clips"), 1);
    redraw("marks");
  }
  function onSelected() {
    selected = new Set(list(model, "selected_units").map(Number));
    redraw("marks");
  }
  function onPinned() {
    pinned = list(model, "pinned_units").map(Number);
    redraw("over");
  }
  function onStatus() {
    root.dataset.status = String(model.get("status") || "idle");
    root.dataset.frames = String(Number(model.get("frame_count")) || 0);
    root.dataset.stale = String(!!model.get("stale"));
    root.dataset.kernel = status.kernel();
    const running = model.get("status") === "running";
    if (running && !(Number(model.get("frame_count")) > 0)) replay.clear(); // a new run
    replay.update(running && status.kernel() !== "gone");
    status.update();
    toolbar.update();
  }

  onModel(model, ["change:design"], onDesign, signal);
  onModel(model, ["change:frame"], onFrame, signal);
  onModel(model, ["change:units", "change:colors", "change:clips"], onUnits, signal);
  onModel(model, ["change:selected_units"], onSelected, signal);
  onModel(model, ["change:pinned_units"], onPinned, signal);
  onModel(model, ["change:status", "change:frame_count", "change:progress", "change:error"], () => (status.answered(), onStatus()), signal);
  onModel(model, ["change:stale"], onStatus, signal);
  onModel(model, ["change:legend_image"], () => legend.place(), signal);
  onModel(model, ["change:pile_labels"], drawLabels, signal);
  onModel(model, ["change:axes_image"], drawAxes, signal);
  onModel(model, ["change:fields"], () => panels[2].update(), signal);
  onModel(model, ["change:marks"], () => {
    bitmaps.update(list(model, "marks"));
    panels[3].update();
    redraw("marks");
  }, signal);
  onModel(model, ["msg:custom"], (msg) => {
    if (msg && msg.type === "export") download(root, msg);
    else if (msg && msg.type === "notice") status.notify(String(msg.text || ""));
    else if (msg && msg.type === "code") {
      copyText(root, String(msg.code || "")).then((ok) =>
        status.notify(ok ? "Copied the design as Python" : "Press Ctrl+C to copy the selected Python"));
    }
  }, signal);
  listen(s.bus, "ui", () => {
    updatePanels();
    redraw("scene", "over");
  }, signal);
  stage.onResize = () => redraw("scene", "over", "marks");

  attachInput(view, tools, signal);
  bitmaps.update(list(model, "marks"));
  onUnits();
  onSelected();
  onPinned();
  onStatus();
  onDesign();
  onFrame();
  stats.framesReceived = 0;
  return view;
}
