// Bundles js/src into one ESM file for anywidget: unitopia_widget/static/widget.js (+ widget.css).
// Deterministic: no timestamps, no absolute paths, so rebuilding unchanged sources is byte-identical.
import { build } from "esbuild";
import { fileURLToPath } from "node:url";
import path from "node:path";

const here = path.dirname(fileURLToPath(import.meta.url));
// UNITOPIA_BUNDLE_DIR builds elsewhere (the staleness test compares that build with the committed one)
const outdir = process.env.UNITOPIA_BUNDLE_DIR || path.join(here, "..", "unitopia_widget", "static");

await build({
  absWorkingDir: here,
  entryPoints: ["src/index.js"],
  outfile: path.join(outdir, "widget.js"),
  bundle: true,
  format: "esm",
  target: "es2020",
  charset: "utf8",
  legalComments: "none",
  minify: false,
  sourcemap: false,
  logLevel: "warning",
});
