//! `canstar generate`: render every requested design to Verilog (and pin
//! files where a board is given) in memory first, then write all files, so
//! that a bad configuration never leaves half-written output.

use anyhow::{bail, Context, Result};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use crate::config::Config;
pub use crate::verilog::{Artifact, Root};

/// What `canstar generate` can produce.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Target {
    /// The shared RTL blocks (CRC-15, stuffer, destuffer, bit timing, synchroniser), each as a standalone module.
    Blocks,
    /// The CAN controller: the core with its native interface, and the SJA1000-compatible Wishbone top.
    Controller,
    /// The star hubs (ReCANcentrate reference hub and CANcentrate) with pin files.
    Hub,
    /// Everything that exists.
    All,
}

/// Render the artifacts of a target without touching the file system.
pub fn render(target: Target, config: &Config, board: Option<&str>) -> Result<Vec<Artifact>> {
    config.validate()?;
    let mut out = vec![];
    if matches!(target, Target::Blocks | Target::All) {
        out.extend(crate::designs::blocks(config)?);
    }
    if matches!(target, Target::Controller | Target::All) {
        out.extend(crate::designs::controller(config)?);
        if config.controller.host_interface {
            out.extend(crate::designs::sja1000(config, board)?);
        }
    }
    if matches!(target, Target::Hub | Target::All) {
        out.extend(crate::designs::hub(config, board)?);
    } else if let Some(b) = board {
        // Still check the name, so a typo is an error whatever the target.
        crate::boards::Board::lookup(b)?;
    }
    // Refuse two artifacts with the same path (a programming error, but cheap to check).
    let mut seen = BTreeMap::new();
    for a in &out {
        if seen.insert((a.root, a.path.clone()), ()).is_some() {
            bail!("two generated files share the path {}", a.path.display());
        }
    }
    Ok(out)
}

fn dest(a: &Artifact, out: &Path, constraints: &Path) -> PathBuf {
    match a.root {
        Root::Verilog => out.join(&a.path),
        Root::Constraints => constraints.join(&a.path),
    }
}

/// Write all artifacts. Every file is first written next to its destination
/// under a temporary name; only when all are written are they renamed into place.
pub fn write(artifacts: &[Artifact], out: &Path, constraints: &Path) -> Result<Vec<PathBuf>> {
    let mut staged = vec![];
    for a in artifacts {
        let d = dest(a, out, constraints);
        let dir = d.parent().unwrap_or(Path::new("."));
        std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
        let tmp = d.with_extension("canstar-tmp");
        if let Err(e) = std::fs::write(&tmp, &a.contents) {
            for (t, _) in &staged {
                let _ = std::fs::remove_file(t);
            }
            return Err(e).with_context(|| format!("writing {}", tmp.display()));
        }
        staged.push((tmp, d));
    }
    let mut written = vec![];
    for (tmp, d) in staged {
        std::fs::rename(&tmp, &d).with_context(|| format!("renaming {} to {}", tmp.display(), d.display()))?;
        written.push(d);
    }
    Ok(written)
}

/// Compare artifacts with the files on disk; returns the paths that differ or are missing.
pub fn check(artifacts: &[Artifact], out: &Path, constraints: &Path) -> Vec<PathBuf> {
    artifacts
        .iter()
        .filter_map(|a| {
            let d = dest(a, out, constraints);
            match std::fs::read_to_string(&d) {
                Ok(s) if s == a.contents => None,
                _ => Some(d),
            }
        })
        .collect()
}

