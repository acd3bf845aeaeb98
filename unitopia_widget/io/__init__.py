"""Input and output: safe SVG and images in, SVG and PNG pages out."""
