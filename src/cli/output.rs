//! Checks on output paths shared by the commands.

use anyhow::Result;
use std::path::Path;

/// The parent directory of an output file must exist (checked before any work).
pub fn check_output(p: &Path) -> Result<()> {
    if p.is_dir() {
        anyhow::bail!("{} is a directory", p.display());
    }
    if let Some(d) = p.parent() {
        if !d.as_os_str().is_empty() && !d.is_dir() {
            anyhow::bail!("cannot write {}: directory {} does not exist", p.display(), d.display());
        }
    }
    Ok(())
}
