// src/story-player.js
var ROOT_CSS = ".story-root{position:absolute;inset:0;width:100%;height:100%;pointer-events:none}";
var BACK_CSS = ROOT_CSS + ".story-root>g.unit{display:none}";
var UNITS_CSS = ROOT_CSS + ".story-root>:not(defs):not(g.unit){display:none}.story-root>g.unit{pointer-events:auto}";
function inert(root) {
  for (const el of Array.from(root.querySelectorAll("script, foreignObject, iframe, object, embed"))) el.remove();
  for (const el of [root, ...root.querySelectorAll("*")]) {
    for (const { name, value } of Array.from(el.attributes)) {
      const link = name === "href" || name.endsWith(":href") || name === "src";
      if (name.toLowerCase().startsWith("on") || link && !value.startsWith("#") && !/^data:image\//i.test(value.trim())) {
        el.removeAttribute(name);
      }
    }
  }
  return root;
}
function layer(stage, svgText, view, css, kind) {
  const host = document.createElement("div");
  host.className = "story-layer story-" + kind;
  host.style.cssText = "position:absolute;inset:0";
  const root = host.attachShadow({ mode: "open" });
  const style = document.createElement("style");
  style.textContent = css;
  const doc = new DOMParser().parseFromString(svgText, "image/svg+xml");
  const svg = document.importNode(inert(doc.documentElement), true);
  svg.classList.add("story-root");
  svg.setAttribute("viewBox", view.join(" "));
  svg.setAttribute("preserveAspectRatio", "xMidYMid meet");
  svg.removeAttribute("width");
  svg.removeAttribute("height");
  root.append(style, svg);
  stage.appendChild(host);
  return { host, units: Array.from(svg.querySelectorAll(":scope > g.unit")) };
}
function place(el, s, box, opacity) {
  el.setAttribute("transform", "translate(" + s[0] + " " + s[1] + ") rotate(" + s[2] + ") scale(" + s[3] / box[0] + " " + s[4] / box[1] + ") translate(" + -box[0] / 2 + " " + -box[1] / 2 + ")");
  el.style.opacity = String(opacity);
}
function ease(t, delay, stagger) {
  const u = Math.min(1, Math.max(0, (t - delay) / (1 - stagger)));
  return u * u * (3 - 2 * u);
}
function transitionAt(data, k, t, draw) {
  const p = data.transitions[k], A = data.slides[k].units, B = data.slides[k + 1].units;
  for (let i = 0; i < p.a.length; i++) {
    const u = ease(t, p.delay[i], data.stagger);
    const sa = p.a[i] >= 0 ? A[p.a[i]] : B[p.b[i]];
    const sb = p.b[i] >= 0 ? B[p.b[i]] : sa;
    const turn = ((sb[2] - sa[2] + 180) % 360 + 360) % 360 - 180;
    const now = [0, 1, 2, 3, 4].map((j) => sa[j] + (sb[j] - sa[j]) * u);
    now[2] = sa[2] + turn * u;
    if (p.a[i] >= 0) draw(0, p.a[i], now, p.fade[i] || p.b[i] < 0 ? 1 - u : u >= 1 ? 0 : 1);
    if (p.b[i] >= 0) draw(1, p.b[i], now, u);
  }
}
function mountStory(el, data, options = {}) {
  const n = data.slides.length;
  let seconds = options.seconds || data.seconds, index = 0, running = null, running_target = 0;
  el.classList.add("unitopia-story");
  const stage = document.createElement("div");
  stage.className = "story-stage";
  stage.style.cssText = "position:relative;width:100%;max-width:" + data.view[2] + "px;aspect-ratio:" + data.view[2] + " / " + data.view[3];
  const bar = document.createElement("div");
  bar.className = "story-controls";
  const prev = document.createElement("button");
  prev.type = "button";
  prev.className = "story-prev";
  prev.textContent = "← Previous";
  const next = document.createElement("button");
  next.type = "button";
  next.className = "story-next";
  next.textContent = "Next →";
  const count = document.createElement("span");
  count.className = "story-count";
  count.setAttribute("aria-live", "polite");
  const speedLabel = document.createElement("label");
  speedLabel.textContent = " Transition ";
  const speed = document.createElement("input");
  speed.type = "range";
  speed.className = "story-speed";
  speed.min = "0.2";
  speed.max = "5";
  speed.step = "0.1";
  speed.value = String(seconds);
  speed.setAttribute("aria-label", "transition seconds");
  const speedText = document.createElement("span");
  speedLabel.append(speed, speedText);
  bar.append(prev, " ", count, " ", next, speedLabel);
  el.append(stage, bar);
  const backs = data.slides.map((s) => layer(stage, s.svg, data.view, BACK_CSS, "back"));
  const fronts = data.slides.map((s) => layer(stage, s.svg, data.view, UNITS_CSS, "units"));
  function rest(k) {
    const units = data.slides[k].units;
    fronts[k].units.forEach((g, i) => place(g, units[i], units[i].slice(5), 1));
  }
  function show(k) {
    index = k;
    for (let j = 0; j < n; j++) {
      backs[j].host.style.opacity = j === k ? "1" : "0";
      fronts[j].host.style.display = j === k ? "" : "none";
      rest(j);
    }
    count.textContent = k + 1 + " / " + n;
    stage.setAttribute("aria-label", data.slides[k].title || "slide " + (k + 1));
    prev.disabled = k === 0;
    next.disabled = k === n - 1;
    el.dataset.slide = String(k);
    el.dataset.moving = "0";
  }
  function frame(k, t) {
    const A = data.slides[k].units, B = data.slides[k + 1].units;
    backs[k].host.style.opacity = "1";
    backs[k + 1].host.style.opacity = String(t);
    transitionAt(data, k, t, (side, i, s, a) => {
      const g = (side ? fronts[k + 1] : fronts[k]).units[i];
      place(g, s, (side ? B : A)[i].slice(5), a);
    });
  }
  function go(target) {
    target = Math.max(0, Math.min(n - 1, target));
    if (running) {
      cancelAnimationFrame(running.id);
      running = null;
      show(running_target);
    }
    if (target === index) return;
    if (Math.abs(target - index) > 1) {
      show(target);
      options.onIndex && options.onIndex(target);
      return;
    }
    const k = Math.min(index, target), forward = target > index;
    for (let j = 0; j < n; j++) {
      backs[j].host.style.opacity = j === k || j === k + 1 ? backs[j].host.style.opacity : "0";
      fronts[j].host.style.display = j === k || j === k + 1 ? "" : "none";
    }
    el.dataset.moving = "1";
    running_target = target;
    const still = window.matchMedia && window.matchMedia("(prefers-reduced-motion: reduce)").matches;
    const start = performance.now(), length = still ? 0 : seconds * 1e3;
    const step = (now) => {
      const s = length > 0 ? Math.min(1, (now - start) / length) : 1;
      frame(k, forward ? s : 1 - s);
      if (s < 1) running = { id: requestAnimationFrame(step) };
      else {
        running = null;
        show(target);
      }
    };
    frame(k, forward ? 0 : 1);
    running = { id: requestAnimationFrame(step) };
    options.onIndex && options.onIndex(target);
  }
  prev.addEventListener("click", () => go((running ? running_target : index) - 1));
  next.addEventListener("click", () => go((running ? running_target : index) + 1));
  (options.keys || el).addEventListener("keydown", (e) => {
    if (e.key === "ArrowRight" || e.key === "ArrowLeft") {
      e.preventDefault();
      go((running ? running_target : index) + (e.key === "ArrowRight" ? 1 : -1));
    }
  });
  if (!options.keys) el.tabIndex = 0;
  function setSeconds(v) {
    seconds = Math.max(0.05, Number(v) || data.seconds);
    speed.value = String(seconds);
    speedText.textContent = " " + seconds.toFixed(1) + " s";
  }
  speed.addEventListener("input", () => {
    setSeconds(speed.value);
    options.onSeconds && options.onSeconds(seconds);
  });
  setSeconds(seconds);
  show(options.index || 0);
  return { go, show, setSeconds, get index() {
    return running ? running_target : index;
  } };
}

// src/story.js
function render({ model, el, signal }) {
  let player = null;
  function mount() {
    el.replaceChildren();
    const data = model.get("story");
    if (!data || !data.slides || !data.slides.length) return;
    player = mountStory(el, data, {
      seconds: model.get("seconds"),
      index: model.get("index"),
      onIndex: (i) => {
        model.set("index", i);
        model.save_changes();
      },
      onSeconds: (s) => {
        model.set("seconds", s);
        model.save_changes();
      }
    });
  }
  const onIndex = () => {
    if (player && player.index !== model.get("index")) player.go(model.get("index"));
  };
  const onSeconds = () => {
    if (player) player.setSeconds(model.get("seconds"));
  };
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
var story_default = { render };
export {
  story_default as default
};
