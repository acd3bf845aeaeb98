// Export replies from Python ({"type": "export", "format", "data"}) become downloads
// through an <a download> with a Blob URL; a "code" reply (w.to_code()) goes to the
// clipboard.

export function exportBlob(format, data) {
  if (format === "svg") return new Blob([String(data)], { type: "image/svg+xml" });
  const text = String(data);
  const comma = text.indexOf(",");
  const header = text.slice(0, comma);
  const body = text.slice(comma + 1);
  const mime = (header.match(/^data:([^;,]+)/) || [])[1] || "image/png";
  if (!header.includes(";base64")) return new Blob([decodeURIComponent(body)], { type: mime });
  const bin = atob(body);
  const bytes = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i++) bytes[i] = bin.charCodeAt(i);
  return new Blob([bytes], { type: mime });
}

export function download(root, msg) {
  const format = msg.format === "png" ? "png" : "svg";
  const url = URL.createObjectURL(exportBlob(format, msg.data));
  const a = document.createElement("a");
  a.href = url;
  a.download = `unitopia.${format}`;
  a.hidden = true;
  root.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10000);
}

/**
 * Copies `text` to the clipboard: navigator.clipboard where the page may use it, else a
 * selected textarea and the copy command. Resolves true when copied; false leaves the
 * textarea in `root`, selected, for the user to copy by hand.
 */
export async function copyText(root, text) {
  try {
    if (navigator.clipboard && window.isSecureContext) {
      await navigator.clipboard.writeText(text);
      return true;
    }
  } catch (err) {
    // refused (no permission, page not focused): the textarea below
  }
  const old = root.querySelector("textarea.ut-code");
  if (old) old.remove();
  const area = document.createElement("textarea");
  area.className = "ut-code";
  area.readOnly = true;
  area.value = text;
  area.setAttribute("aria-label", "The design as Python");
  root.append(area);
  area.select();
  let copied = false;
  try {
    copied = document.execCommand("copy");
  } catch (err) {
    copied = false;
  }
  if (copied) area.remove();
  return copied;
}
