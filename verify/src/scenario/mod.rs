//! Bus scenario files for `canstar sim`: nodes, bit timing, clock offsets,
//! frames to send at given times, and receive-path interference at given
//! times or protocol positions. TOML, read with serde; unknown keys and
//! impossible values are errors that name the problem.
//!
//! ```toml
//! seed = 1
//! duration_us = 400
//!
//! [defaults]
//! clock_mhz = 10.0                       # 100 ns clock
//! bit_timing = { brp = 1, prop = 1, ph1 = 4, sjw = 4 }
//!
//! [[node]]
//! name = "n1"
//!
//! [[node]]
//! name = "n2"
//! ppm = 100.0
//! rx_delay_ns = 50
//!
//! [[frame]]
//! node = "n1"
//! at_us = 20
//! id = 0x123
//! data = [0x11, 0x22]                    # dlc defaults to the data length
//!
//! [[interference]]
//! node = "n2"
//! mode = "invert"
//! at = { field = "Data_Field", pos = 3 } # or at_us = 55
//! bits = 1
//! ```

use canstar_hdl::timing::BtlConfig;
use canstar_sim::net::FaultMode;
use serde::Deserialize;
use std::fmt::Write as _;

mod check;
mod run;
pub use check::{MAX_DELAY_NS, MAX_DURATION_US, MAX_INTERFERENCE_BITS};
pub use run::{run, NodeSummary, RunOptions, RunResult};

/// Values every node takes unless it sets its own.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Defaults {
    pub clock_mhz: f64,
    pub bit_timing: BtlConfig,
}

impl Default for Defaults {
    fn default() -> Self {
        Self { clock_mhz: 10.0, bit_timing: BtlConfig::T10_6_4 }
    }
}

/// Controller operating mode of a node.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum NodeMode {
    #[default]
    Normal,
    ListenOnly,
    SelfTest,
}

#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NodeSpec {
    pub name: String,
    #[serde(default)]
    pub clock_mhz: Option<f64>,
    #[serde(default)]
    pub ppm: f64,
    #[serde(default)]
    pub bit_timing: Option<BtlConfig>,
    /// TX to bus delay (both edges), ns.
    #[serde(default)]
    pub tx_delay_ns: u64,
    /// Bus to RX delay, ns.
    #[serde(default)]
    pub rx_delay_ns: u64,
    #[serde(default)]
    pub mode: NodeMode,
    /// Single shot: no automatic retransmission.
    #[serde(default)]
    pub single_shot: bool,
}

#[derive(Debug, Clone, PartialEq, Eq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FrameSpec {
    pub node: String,
    /// When the host requests the frame.
    pub at_us: u64,
    pub id: u32,
    #[serde(default)]
    pub ext: bool,
    #[serde(default)]
    pub rtr: bool,
    /// Data length code 0..=15; defaults to the number of data bytes.
    #[serde(default)]
    pub dlc: Option<u8>,
    #[serde(default)]
    pub data: Vec<u8>,
}

impl FrameSpec {
    pub fn dlc(&self) -> u8 {
        self.dlc.unwrap_or(self.data.len() as u8)
    }
}


/// A protocol position (FIELD name of can-protocol.md §4.5, 1-based position).
#[derive(Debug, Clone, PartialEq, Eq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Position {
    pub field: String,
    #[serde(default = "one")]
    pub pos: u32,
    /// Which occurrence of that position counts (1 = the first).
    #[serde(default = "one")]
    pub occurrence: u32,
}

fn one() -> u32 {
    1
}

/// FIELD names a position may use (can-protocol.md §4.5).
pub const FIELD_NAMES: &[&str] = &[
    "Bus_Idle", "Start_Of_Frame", "Identifier", "SRR_Bit", "IDE_Bit", "Ex_Identifier", "RTR_Bit",
    "Reserved_Bits", "Data_Length_Code", "Data_Field", "CRC_Sequence", "CRC_Delimiter", "ACK_Slot",
    "ACK_Delimiter", "End_Of_Frame", "Intermission", "Suspend_Transmission", "Active_Error_Flag",
    "Passive_Error_Flag", "Overload_Flag", "Error_Delimiter", "Overload_Delimiter",
];

#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InterferenceSpec {
    pub node: String,
    pub mode: FaultMode,
    /// Start at a simulated time ...
    #[serde(default)]
    pub at_us: Option<f64>,
    /// ... or at the start of a bit the node reaches.
    #[serde(default)]
    pub at: Option<Position>,
    /// Duration in nominal bit times of that node; absent = until the end.
    #[serde(default)]
    pub bits: Option<u32>,
}

/// A whole scenario.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scenario {
    #[serde(default = "default_seed")]
    pub seed: u64,
    /// Simulated time to run.
    pub duration_us: u64,
    #[serde(default)]
    pub defaults: Defaults,
    #[serde(rename = "node")]
    pub nodes: Vec<NodeSpec>,
    #[serde(rename = "frame", default)]
    pub frames: Vec<FrameSpec>,
    #[serde(rename = "interference", default)]
    pub interference: Vec<InterferenceSpec>,
}

fn default_seed() -> u64 {
    1
}

impl Scenario {
    /// Parse and check a scenario; the error names the problem.
    pub fn from_toml(text: &str) -> Result<Self, String> {
        let s: Scenario = toml::from_str(text).map_err(|e| format!("malformed scenario: {e}"))?;
        s.validate()?;
        Ok(s)
    }

    pub fn node_index(&self, name: &str) -> Option<usize> {
        self.nodes.iter().position(|n| n.name == name)
    }

    pub fn bit_timing(&self, node: usize) -> BtlConfig {
        self.nodes[node].bit_timing.unwrap_or(self.defaults.bit_timing)
    }

    pub fn clock_mhz(&self, node: usize) -> f64 {
        self.nodes[node].clock_mhz.unwrap_or(self.defaults.clock_mhz)
    }

    /// Check every value (see [`check`]); the error starts with the key.
    pub fn validate(&self) -> Result<(), String> {
        check::validate(self)
    }
}

/// One line of a candump log file: `(seconds.micro) canN ID#DATA`, with
/// `ID#R` for remote frames (`ID#R<len>` when the DLC is not 0). Standard
/// identifiers have 3 hex digits, extended ones 8. A data frame with a raw
/// DLC of 9..15 is written with its 8 data bytes and no DLC suffix: newer
/// can-utils accept `_X` for the raw DLC, but python-can (4.6) rejects it.
pub fn candump_line(t_ps: u64, iface: &str, ext: bool, id: u32, rtr: bool, dlc: u8, data: &[u8]) -> String {
    let mut s = String::new();
    let us = t_ps / 1_000_000;
    write!(s, "({}.{:06}) {iface} ", us / 1_000_000, us % 1_000_000).unwrap();
    if ext {
        write!(s, "{id:08X}#").unwrap();
    } else {
        write!(s, "{id:03X}#").unwrap();
    }
    if rtr {
        s.push('R');
        if dlc > 0 && dlc <= 8 {
            write!(s, "{dlc}").unwrap();
        }
    } else {
        for b in data {
            write!(s, "{b:02X}").unwrap();
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    const OK: &str = r#"
duration_us = 100
[[node]]
name = "n1"
[[node]]
name = "n2"
ppm = 50
[[frame]]
node = "n1"
at_us = 5
id = 0x123
data = [1, 2]
[[interference]]
node = "n2"
mode = "invert"
at = { field = "Data_Field", pos = 3 }
bits = 1
"#;

    #[test]
    fn parses_a_valid_scenario() {
        let s = Scenario::from_toml(OK).unwrap();
        assert_eq!(s.nodes.len(), 2);
        assert_eq!(s.frames[0].dlc(), 2);
        assert_eq!(s.interference[0].at.as_ref().unwrap().pos, 3);
    }

    #[test]
    fn rejects_bad_scenarios_with_clear_messages() {
        for (edit, expect) in [
            (OK.replace("ppm = 50", "ppm = 50\nwobble = 1"), "unknown field"),
            (OK.replace("node = \"n1\"\nat_us", "node = \"n9\"\nat_us"), "unknown node `n9`"),
            (OK.replace("id = 0x123", "id = 0x923"), "does not fit a 11-bit frame"),
            (OK.replace("data = [1, 2]", "data = [1, 2]\ndlc = 5"), "2 data byte(s) given"),
            (OK.replace("\"Data_Field\"", "\"Data\""), "unknown field `Data`"),
            (OK.replace("ppm = 50", "ppm = 50\nbit_timing = { brp = 1, prop = 1, ph1 = 2, sjw = 1 }"), "invalid bit timing"),
            (OK.replace("name = \"n2\"", "name = \"n1\""), "used twice"),
            (OK.replace("duration_us = 100", ""), "missing field `duration_us`"),
            (OK.replace("bits = 1", "bits = 1\nat_us = 3.0"), "either at_us or at"),
            // issue #15: overflow and NaN
            (OK.replace("duration_us = 100", "duration_us = 18446744073710"), "duration_us: 18446744073710 (must be 1..="),
            (OK.replace("at_us = 5", "at_us = 18446744073710"), "frame[0].at_us: 18446744073710 is not before the end"),
            (OK.replace("ppm = 50", "ppm = nan"), "node[1].ppm: NaN (node n2) is not an oscillator offset"),
            (OK.replace("ppm = 50", "ppm = inf"), "node[1].ppm: inf"),
            (OK.replace("at = { field = \"Data_Field\", pos = 3 }", "at_us = nan"), "interference[0].at_us: NaN"),
            (OK.replace("at = { field = \"Data_Field\", pos = 3 }", "at_us = 1e300"), "interference[0].at_us"),
            (OK.replace("bits = 1", "bits = 4000000000"), "interference[0].bits: 4000000000"),
            (OK.replace("ppm = 50", "ppm = 50\nrx_delay_ns = 18446744073709551"), "node[1].rx_delay_ns"),
            (OK.replace("name = \"n2\"", "name = \"n 2\""), "node[1].name: name `n 2` must be"),
        ] {
            let e = Scenario::from_toml(&edit).unwrap_err();
            assert!(e.contains(expect), "expected `{expect}` in `{e}`");
        }
    }

    #[test]
    fn candump_lines() {
        assert_eq!(candump_line(1_500_000_000, "can0", false, 0x123, false, 2, &[0x11, 0xAB]), "(0.001500) can0 123#11AB");
        assert_eq!(candump_line(2_000_001_000_000, "can1", true, 0x1ABCDE, false, 0, &[]), "(2.000001) can1 001ABCDE#");
        assert_eq!(candump_line(0, "can0", false, 0x7FF, true, 0, &[]), "(0.000000) can0 7FF#R");
        assert_eq!(candump_line(0, "can0", false, 0x10, true, 3, &[]), "(0.000000) can0 010#R3");
        assert_eq!(candump_line(0, "can0", false, 0x10, false, 12, &[0; 8]), "(0.000000) can0 010#0000000000000000");
    }
}
