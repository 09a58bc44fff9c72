"""Stage 6, `make_shells` and `write_step`: the mid-surface as shells, written as STEP with per-face attributes and a glTF preview."""
