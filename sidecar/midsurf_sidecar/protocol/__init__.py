"""Request plumbing without OCP (the server imports it before the handshake): typed args, errors carrying a protocol code, the handle store."""
