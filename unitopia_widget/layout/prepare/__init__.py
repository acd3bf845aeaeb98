"""What a layout makes once, before its first step: the bound units, the start scales and
positions, the fields and sprites, assembled into the solver's ``Problem``. Imports
``step/`` (the raster and loss types it fills), never ``rules/`` or the solver."""
