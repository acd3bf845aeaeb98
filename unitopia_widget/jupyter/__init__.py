"""The Jupyter widget: traitlets, the background runner, the saved output."""
