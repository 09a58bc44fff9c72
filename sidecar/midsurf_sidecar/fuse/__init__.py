"""Stage 4, `fuse`: patches split where they cross, each face traced back to its patch, T-joints ending inside a face split through."""
