"""Stage 2, `describe`: the face graph of a solid (faces with surface kind, loops, edges with convexity, optional meshes) that Rust pairs faces on."""
