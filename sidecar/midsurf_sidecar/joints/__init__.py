"""Stage 5, `probe_edges` and `extend_edges`: what lies beyond a patch's free edges, and the strips and corner quads that grow them to their partners."""
