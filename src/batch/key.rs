//! Resume keys: a part is done when what made its outputs is unchanged. A key is the SHA-256 of the input's
//! content, the part's `midsurf run` options, the midsurf version, and the code that ran: the executable
//! itself and the sidecar's Python sources (a rebuild or an edit of either makes every part run again).

use std::io::Read;
use std::path::Path;

use sha2::{Digest, Sha256};

fn hex(digest: &[u8]) -> String {
    digest.iter().map(|b| format!("{b:02x}")).collect()
}

/// SHA-256 of a file's content, streamed (parts can be hundreds of MB).
pub fn file_sha256(path: &Path) -> std::io::Result<String> {
    let mut file = std::fs::File::open(path)?;
    let mut hasher = Sha256::new();
    let mut buf = vec![0u8; 1 << 16];
    loop {
        let n = file.read(&mut buf)?;
        if n == 0 {
            break;
        }
        hasher.update(&buf[..n]);
    }
    Ok(hex(&hasher.finalize()))
}

/// The code that makes the outputs: this executable and the sidecar's Python sources (every `*.py` under
/// `sidecar_package`, walked in sorted order, each hashed with its relative path).
pub fn code_sha256(exe: &Path, sidecar_package: Option<&Path>) -> std::io::Result<String> {
    let mut hasher = Sha256::new();
    hasher.update(env!("CARGO_PKG_VERSION").as_bytes());
    hasher.update(b"\0");
    hasher.update(file_sha256(exe)?.as_bytes());
    if let Some(dir) = sidecar_package {
        let mut files = Vec::new();
        python_files(dir, dir, &mut files)?;
        files.sort();
        for (rel, path) in files {
            hasher.update(rel.as_bytes());
            hasher.update(b"\0");
            hasher.update(file_sha256(&path)?.as_bytes());
        }
    }
    Ok(hex(&hasher.finalize()))
}

fn python_files(root: &Path, dir: &Path, out: &mut Vec<(String, std::path::PathBuf)>) -> std::io::Result<()> {
    for entry in std::fs::read_dir(dir)? {
        let path = entry?.path();
        if path.is_dir() {
            if path.file_name().is_some_and(|n| n != "__pycache__") {
                python_files(root, &path, out)?;
            }
        } else if path.extension().is_some_and(|e| e == "py") {
            let rel = path.strip_prefix(root).unwrap_or(&path).to_string_lossy().into_owned();
            out.push((rel, path));
        }
    }
    Ok(())
}

/// The key of one part: its input's content hash, its run arguments and the code's hash.
pub fn part_key(input_sha: &str, run_args: &[String], code_sha: &str) -> String {
    let mut hasher = Sha256::new();
    for piece in [input_sha, &run_args.join("\0"), code_sha] {
        hasher.update(piece.as_bytes());
        hasher.update(b"\n");
    }
    hex(&hasher.finalize())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sha256_of_a_known_text() {
        let path = std::env::temp_dir().join(format!("midsurf-key-test-{}", std::process::id()));
        std::fs::write(&path, b"abc").unwrap();
        let got = file_sha256(&path).unwrap();
        std::fs::remove_file(&path).unwrap();
        assert_eq!(got, "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
    }

    #[test]
    fn keys_change_with_each_ingredient() {
        let args = vec!["--t-max=2".to_string()];
        let base = part_key("in", &args, "code");
        assert_ne!(base, part_key("in2", &args, "code"));
        assert_ne!(base, part_key("in", &[], "code"));
        assert_ne!(base, part_key("in", &args, "code2"));
        assert_eq!(base, part_key("in", &args, "code"));
    }
}
