// Bundles js/src for anywidget into unitopia_widget/static/: the chart widget (widget.js +
// widget.css), the story widget (story.js) and the one-file story page's script (story-page.js).
// Deterministic: no timestamps, no absolute paths, so rebuilding unchanged sources is byte-identical.
import { build } from "esbuild";
import { fileURLToPath } from "node:url";
import path from "node:path";

const here = path.dirname(fileURLToPath(import.meta.url));
// UNITOPIA_BUNDLE_DIR builds elsewhere (the staleness test compares that build with the committed one)
const outdir = process.env.UNITOPIA_BUNDLE_DIR || path.join(here, "..", "unitopia_widget", "static");
const BUNDLES = [
  { entry: "src/index.js", out: "widget.js", format: "esm" },
  { entry: "src/story.js", out: "story.js", format: "esm" },
  { entry: "src/story-page.js", out: "story-page.js", format: "iife" },
];

for (const { entry, out, format } of BUNDLES) {
  await build({
    absWorkingDir: here,
    entryPoints: [entry],
    outfile: path.join(outdir, out),
    bundle: true,
    format,
    target: "es2020",
    charset: "utf8",
    legalComments: "none",
    minify: false,
    sourcemap: false,
    logLevel: "warning",
  });
}
