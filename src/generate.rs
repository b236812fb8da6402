//! `canstar generate`: render every requested design to Verilog (and pin
//! files where a board is given) in memory first, then write all files as one
//! [`OutputSet`], so that a bad configuration or an unwritable destination
//! never leaves half-written output.

use anyhow::{bail, Result};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use crate::config::Config;
use crate::output::OutputSet;
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
            out.extend(crate::designs::slcan(config, board)?);
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

/// Stage every artifact in `set` (each under a temporary name next to its
/// destination, missing directories created); [`OutputSet::commit`] moves them
/// into place together.
pub fn stage(set: &mut OutputSet, artifacts: &[Artifact], out: &Path, constraints: &Path) -> Result<()> {
    for a in artifacts {
        let d = dest(a, out, constraints);
        set.file_creating_dirs(&d)?;
        set.write(&d, &a.contents)?;
    }
    Ok(())
}

/// Write all artifacts as one set: nothing changes on disk unless every file
/// could be written.
pub fn write(artifacts: &[Artifact], out: &Path, constraints: &Path) -> Result<Vec<PathBuf>> {
    let mut set = OutputSet::new();
    set.root(out)?;
    set.root(constraints)?;
    stage(&mut set, artifacts, out, constraints)?;
    set.commit()
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

