"""Stage 3, `make_patch`: mid-patches, each reference face offset or projected, its suppressed features' loops filled, clipped to its partners' footprint."""
