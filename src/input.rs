//! Reading input files: bounded in size, UTF-8, and every failure named with
//! the path (`x.toml: is a directory`, `x.toml: larger than 16 MiB`).

use anyhow::{bail, Result};
use std::io::Read;
use std::path::Path;

/// Largest configuration, board, scenario or network file read (a real one is
/// a few kB; a scenario with thousands of frames stays far below).
pub const MAX_TOML_BYTES: u64 = 16 << 20;

/// Largest JSON campaign report read by `campaign --merge`.
pub const MAX_JSON_BYTES: u64 = 1 << 30;

fn mib(n: u64) -> String {
    if n >= 1 << 20 {
        format!("{} MiB", n >> 20)
    } else {
        format!("{n} bytes")
    }
}

/// Read a text file of at most `limit` bytes. Devices and pipes are read up to
/// the limit too (`/dev/zero` stops with an error instead of filling memory).
pub fn read_text(path: &Path, limit: u64) -> Result<String> {
    let p = path.display();
    if path.is_dir() {
        bail!("{p}: is a directory, not a file");
    }
    let f = std::fs::File::open(path).map_err(|e| anyhow::anyhow!("{p}: cannot read: {e}"))?;
    let mut bytes = vec![];
    f.take(limit + 1).read_to_end(&mut bytes).map_err(|e| anyhow::anyhow!("{p}: cannot read: {e}"))?;
    if bytes.len() as u64 > limit {
        bail!("{p}: larger than {} (not an input file of this tool?)", mib(limit));
    }
    match String::from_utf8(bytes) {
        Ok(s) => Ok(s),
        Err(e) => {
            let at = e.utf8_error().valid_up_to();
            let line = e.as_bytes()[..at].iter().filter(|&&b| b == b'\n').count() + 1;
            bail!("{p}: not UTF-8 text (invalid byte at line {line})")
        }
    }
}

/// [`read_text`] with the TOML limit.
pub fn read_toml(path: &Path) -> Result<String> {
    read_text(path, MAX_TOML_BYTES)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unreadable_inputs_name_the_path() {
        let d = tempfile::tempdir().unwrap();
        let e = read_toml(d.path()).unwrap_err().to_string();
        assert!(e.contains(&d.path().display().to_string()) && e.contains("is a directory"), "{e}");
        let e = read_toml(&d.path().join("nope.toml")).unwrap_err().to_string();
        assert!(e.contains("nope.toml: cannot read"), "{e}");
        std::fs::write(d.path().join("bin.toml"), b"a = 1\n\xff\xfe").unwrap();
        let e = read_toml(&d.path().join("bin.toml")).unwrap_err().to_string();
        assert!(e.contains("bin.toml: not UTF-8 text (invalid byte at line 2)"), "{e}");
        std::fs::write(d.path().join("big.toml"), vec![b'#'; 2000]).unwrap();
        let e = read_text(&d.path().join("big.toml"), 1000).unwrap_err().to_string();
        assert!(e.contains("big.toml: larger than"), "{e}");
        assert_eq!(read_text(&d.path().join("big.toml"), 2000).unwrap().len(), 2000);
    }

    #[test]
    fn an_endless_device_stops_at_the_limit() {
        if Path::new("/dev/zero").exists() {
            let e = read_text(Path::new("/dev/zero"), 1 << 16).unwrap_err().to_string();
            assert!(e.contains("/dev/zero: larger than"), "{e}");
        }
    }
}
