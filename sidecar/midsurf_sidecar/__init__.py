"""The OCCT side of midsurf: answers NDJSON requests from the Rust binary (see ../PROTOCOL.md)."""
