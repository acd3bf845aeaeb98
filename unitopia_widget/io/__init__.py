"""Safe input: SVG sanitising and image readers."""
