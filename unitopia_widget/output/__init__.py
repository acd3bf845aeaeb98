"""Output: the exported SVG and PNG page (marks, legend, title, outlines), built from a layout."""
