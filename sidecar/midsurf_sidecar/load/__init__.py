"""Stage 1, `load_step`: the solids of a STEP file."""
