"""The design model: marks, containers, emitters, forces, layers and encodings."""
