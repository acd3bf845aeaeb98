// unitopia_widget front end (anywidget 0.11 module shape).
import "./widget.css";
import { session } from "./model-sync.js";
import { renderView } from "./view.js";

export default {
  initialize({ model }) {
    session(model); // history and UI state shared by every view of this model
  },
  render({ model, el, signal }) {
    const controller = signal ? null : new AbortController();
    renderView({ model, el, signal: signal || controller.signal });
    return controller ? () => controller.abort() : undefined;
  },
};
