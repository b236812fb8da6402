//! The registry of generatable designs and benchmarks.
use crate::config::Config;
use crate::generate::Artifact;
use anyhow::Result;

/// The shared RTL blocks as standalone modules.
pub fn blocks(_config: &Config) -> Result<Vec<Artifact>> {
    Ok(vec![])
}

/// `canstar bench`.
pub fn bench(_cycles: u64, _nodes: &[usize]) -> Result<()> {
    anyhow::bail!("bench not available yet")
}
