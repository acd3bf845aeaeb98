// SVG path data helpers (containers of kind "path").

const ARGS = { M: 2, L: 2, T: 2, H: 1, V: 1, C: 6, S: 4, Q: 4, A: 7, Z: 0 };
const TOKEN = /([MLHVCSQTAZmlhvcsqtaz])|(-?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)/g;

/**
 * Translates path data by (dx, dy). Absolute coordinates move; relative ones do not,
 * except a leading relative "m", whose first pair is absolute by the SVG rules.
 */
export function translatePathData(d, dx, dy) {
  const out = [];
  let cmd = null;
  let args = [];
  let first = true;
  const flush = () => {
    if (!cmd) return;
    const upper = cmd.toUpperCase();
    const n = ARGS[upper];
    if (n === 0) return void out.push(cmd);
    for (let k = 0; k + n <= args.length; k += n) {
      const a = args.slice(k, k + n);
      const absolute = cmd === upper || (first && cmd === "m" && k === 0);
      if (absolute) shift(upper, a, dx, dy);
      // After the first pair, further pairs of an "M" are implicit "L"s.
      out.push(k === 0 ? cmd : "", ...a.map(fmt));
      first = false;
    }
  };
  for (const m of String(d).matchAll(TOKEN)) {
    if (m[1]) {
      flush();
      cmd = m[1];
      args = [];
    } else {
      args.push(Number(m[2]));
    }
  }
  flush();
  return out.filter((t) => t !== "").join(" ");
}

function shift(upper, a, dx, dy) {
  if (upper === "H") a[0] += dx;
  else if (upper === "V") a[0] += dy;
  else if (upper === "A") {
    a[5] += dx;
    a[6] += dy;
  } else {
    for (let j = 0; j < a.length; j += 2) {
      a[j] += dx;
      a[j + 1] += dy;
    }
  }
}

const fmt = (v) => String(Math.round(v * 1000) / 1000);
