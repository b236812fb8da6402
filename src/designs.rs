//! The registry of generatable designs and benchmarks.
use crate::config::Config;
use crate::generate::{block, Artifact};
use anyhow::Result;
use canstar_hdl::{crc15, stuff, sync};

/// The shared RTL blocks as standalone modules (`verilog-out/blocks/`).
pub fn blocks(config: &Config) -> Result<Vec<Artifact>> {
    Ok(vec![
        block(
            sync::Synchroniser::new(config.rtl.sync_depth),
            "canstar_synchroniser",
            &format!("input synchroniser, {} flip-flop(s), reset value recessive", config.rtl.sync_depth),
        ),
        block(sync::EdgeDetector::default(), "canstar_edge_detector", "edge detector"),
        block(crc15::Crc15::default(), "canstar_crc15", "CAN CRC-15, polynomial 0x4599"),
        block(stuff::BitStuffer::default(), "canstar_bit_stuffer", "CAN bit stuffer"),
        block(stuff::BitDestuffer::default(), "canstar_bit_destuffer", "CAN bit destuffer"),
    ])
}

/// `canstar bench`.
pub fn bench(_cycles: u64, _nodes: &[usize]) -> Result<()> {
    anyhow::bail!("bench not available yet")
}
