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
use serde::Deserialize;
use std::fmt::Write as _;

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

    pub fn validate(&self) -> Result<(), String> {
        if self.nodes.is_empty() {
            return Err("a scenario needs at least one [[node]]".into());
        }
        if self.duration_us == 0 {
            return Err("duration_us must be positive".into());
        }
        self.defaults.bit_timing.check().map_err(|e| format!("defaults: invalid bit timing: {e}"))?;
        for (i, n) in self.nodes.iter().enumerate() {
            if n.name.is_empty() || !n.name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
                return Err(format!("node {}: name `{}` must be non-empty letters, digits or _", i + 1, n.name));
            }
            if self.nodes[..i].iter().any(|m| m.name == n.name) {
                return Err(format!("node name `{}` is used twice", n.name));
            }
            let mhz = self.clock_mhz(i);
            if !(mhz > 0.1 && mhz <= 1000.0) {
                return Err(format!("node {}: clock_mhz = {mhz} (must be in (0.1, 1000])", n.name));
            }
            if n.ppm.abs() > 10_000.0 {
                return Err(format!("node {}: ppm = {} is not an oscillator offset (|ppm| <= 10000)", n.name, n.ppm));
            }
            self.bit_timing(i).check().map_err(|e| format!("node {}: invalid bit timing: {e}", n.name))?;
        }
        for (k, f) in self.frames.iter().enumerate() {
            let what = format!("frame {} (node {})", k + 1, f.node);
            if self.node_index(&f.node).is_none() {
                return Err(format!("{what}: unknown node `{}`", f.node));
            }
            let max = if f.ext { 0x1FFF_FFFF } else { 0x7FF };
            if f.id > max {
                return Err(format!("{what}: identifier {:#x} does not fit a {} frame (max {max:#x})", f.id, if f.ext { "29-bit" } else { "11-bit" }));
            }
            if f.dlc() > 15 {
                return Err(format!("{what}: dlc {} (must be 0..=15)", f.dlc()));
            }
            let n = if f.rtr { 0 } else { f.dlc().min(8) as usize };
            if f.data.len() != n {
                return Err(format!(
                    "{what}: {} data byte(s) given, a {} frame with dlc {} carries {n}",
                    f.data.len(),
                    if f.rtr { "remote" } else { "data" },
                    f.dlc()
                ));
            }
        }
        for (k, x) in self.interference.iter().enumerate() {
            let what = format!("interference {} (node {})", k + 1, x.node);
            if self.node_index(&x.node).is_none() {
                return Err(format!("{what}: unknown node `{}`", x.node));
            }
            match (&x.at_us, &x.at) {
                (Some(_), Some(_)) => return Err(format!("{what}: give either at_us or at, not both")),
                (None, None) => return Err(format!("{what}: give at_us or at = {{ field = ..., pos = ... }}")),
                (Some(t), None) if *t < 0.0 => return Err(format!("{what}: at_us must not be negative")),
                (None, Some(p)) => {
                    if !FIELD_NAMES.contains(&p.field.as_str()) {
                        return Err(format!("{what}: unknown field `{}` (one of: {})", p.field, FIELD_NAMES.join(", ")));
                    }
                    if p.pos == 0 || p.occurrence == 0 {
                        return Err(format!("{what}: pos and occurrence count from 1"));
                    }
                }
                _ => {}
            }
            if x.bits == Some(0) {
                return Err(format!("{what}: bits must be at least 1"));
            }
        }
        Ok(())
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

// ---------------------------------------------------------------------------
// Running a scenario
// ---------------------------------------------------------------------------

use canstar_sim::bus::{Bus, NodeDelays};
use canstar_sim::{Component, Handle, Sim};
use canstar_sim::net::FaultMode;
use crate::node::{CanNode, HostEvent, NodeConfig};
use canstar_controller::frame::Frame;
use canstar_controller::view::CoreView;

/// What to record while running.
#[derive(Debug, Clone, Default)]
pub struct RunOptions {
    /// Write a VCD of every signal and wire here.
    pub vcd: Option<std::path::PathBuf>,
    /// Record the per-bit trace (can-protocol.md §18) of every node.
    pub trace: bool,
    /// Simulation engine of the controllers (compiled models by default).
    pub engine: crate::node::Engine,
}

/// Per-node outcome.
#[derive(Debug, Clone, PartialEq)]
pub struct NodeSummary {
    pub name: String,
    pub sent: usize,
    pub received: usize,
    pub errors: usize,
    pub tec: u32,
    pub rec: u32,
    /// 0 error-active, 1 error-passive, 2 bus-off.
    pub state: u32,
    /// Frames still queued or being sent at the end.
    pub pending: bool,
}

/// The result of a run.
#[derive(Debug, Clone, Default)]
pub struct RunResult {
    /// §18 trace lines (header first), sorted by time and node.
    pub trace: Vec<String>,
    /// candump log lines (`(seconds.micro) canN ID#DATA`), node i is `can<i>`;
    /// each node's own successfully sent frames appear too, as with SocketCAN's
    /// default local loopback.
    pub candump: Vec<String>,
    pub nodes: Vec<NodeSummary>,
}


fn frame_of(f: &FrameSpec) -> Frame {
    if f.rtr {
        Frame::remote(f.ext, f.id, f.dlc())
    } else {
        Frame::data(f.ext, f.id, f.dlc(), &f.data)
    }
}

fn candump_of(t_ps: u64, node: usize, f: &Frame) -> (u64, usize, String) {
    let data = f.data.clone();
    (t_ps, node, candump_line(t_ps, &format!("can{node}"), f.ide, f.id, f.rtr, f.dlc, &data))
}

/// Run a scenario on the RTL controller, one [`CanNode`] per `[[node]]` on a
/// wired-AND bus with the given delays and clock offsets.
pub fn run(s: &Scenario, opts: &RunOptions) -> Result<RunResult, String> {
    s.validate()?;
    let mut sim = Sim::new(s.seed);
    let spec: Vec<(&str, NodeDelays)> = s
        .nodes
        .iter()
        .map(|n| (n.name.as_str(), NodeDelays::symmetric(n.tx_delay_ns * 1000, n.rx_delay_ns * 1000)))
        .collect();
    let bus = Bus::build(&mut sim, "bus", &spec);
    let mut handles: Vec<Handle<CanNode>> = vec![];
    let mut tq_ps = vec![];
    for (i, n) in s.nodes.iter().enumerate() {
        let bt = s.bit_timing(i);
        let mut cfg = NodeConfig::named(&n.name);
        cfg.timing = bt;
        cfg.listen_only = n.mode == NodeMode::ListenOnly;
        cfg.self_test = n.mode == NodeMode::SelfTest;
        cfg.single_shot = n.single_shot;
        cfg.engine = opts.engine;
        let period = (1e6 / s.clock_mhz(i)).round() as u64;
        let clock = sim.random_phase_clock(period, n.ppm);
        tq_ps.push(period * bt.brp as u64);
        let mut node = CanNode::new(cfg, clock);
        if opts.trace {
            node.enable_trace(&format!("D{}", i + 1));
        }
        handles.push(sim.add(node, &[bus.nodes[i].rx], &[bus.nodes[i].tx]));
    }
    if let Some(p) = &opts.vcd {
        sim.start_vcd_file(p, None).map_err(|e| format!("cannot write VCD {}: {e}", p.display()))?;
    }
    let end = s.duration_us * 1_000_000;
    // Frame requests in time order.
    let mut reqs: Vec<&FrameSpec> = s.frames.iter().collect();
    reqs.sort_by_key(|f| f.at_us);
    let mut next_req = 0;
    // Interference: time-based ones are scheduled now; position-based ones
    // are armed and watched.
    struct Armed {
        node: usize,
        mode: FaultMode,
        field: String,
        pos: u32,
        left: u32,
        bits: Option<u32>,
        was_on_target: bool,
    }
    let mut armed = vec![];
    for x in &s.interference {
        let i = s.node_index(&x.node).unwrap();
        let ntq = s.bit_timing(i).ntq() as u64;
        match (&x.at_us, &x.at) {
            (Some(t), _) => {
                let t0 = (t * 1e6).round() as u64;
                bus.schedule_interference(&mut sim, i, t0, x.mode);
                if let Some(b) = x.bits {
                    bus.schedule_interference(&mut sim, i, t0 + b as u64 * ntq * tq_ps[i], FaultMode::None);
                }
            }
            (None, Some(p)) => armed.push(Armed {
                node: i,
                mode: x.mode,
                field: p.field.clone(),
                pos: p.pos,
                left: p.occurrence,
                bits: x.bits,
                was_on_target: false,
            }),
            _ => unreachable!("validated"),
        }
    }
    let mut last_sample = vec![0u64; s.nodes.len()];
    while sim.now() < end {
        while next_req < reqs.len() && reqs[next_req].at_us * 1_000_000 <= sim.now() {
            let f = reqs[next_req];
            let i = s.node_index(&f.node).unwrap();
            sim.get_mut(handles[i]).request(frame_of(f));
            next_req += 1;
        }
        let t = sim.step();
        if t > end {
            break;
        }
        for (i, h) in handles.iter().enumerate() {
            if sim.get(*h).core.dbg_sample() {
                last_sample[i] = t;
            }
        }
        for a in armed.iter_mut().filter(|a| a.left > 0) {
            let n = sim.get(handles[a.node]);
            let on = n.field().name() == a.field && n.pos() == a.pos && !n.core.dbg_sample();
            if on && !a.was_on_target {
                a.left -= 1;
                if a.left == 0 {
                    // The bit before the target has been sampled: start at the
                    // end of its phase segment 2, i.e. the start of the target bit.
                    let bt = s.bit_timing(a.node);
                    let start = (last_sample[a.node] + bt.ph2() as u64 * tq_ps[a.node]).max(t);
                    bus.schedule_interference(&mut sim, a.node, start, a.mode);
                    if let Some(b) = a.bits {
                        let stop = start + b as u64 * bt.ntq() as u64 * tq_ps[a.node];
                        bus.schedule_interference(&mut sim, a.node, stop, FaultMode::None);
                    }
                }
            }
            a.was_on_target = on;
        }
    }
    if opts.vcd.is_some() {
        sim.finish_vcd().map_err(|e| format!("cannot write VCD: {e}"))?;
    }
    let mut result = RunResult::default();
    let mut dump = vec![];
    let mut trace: Vec<(u64, usize, String)> = vec![];
    for (i, h) in handles.iter().enumerate() {
        let n = sim.get(*h);
        for (t, e) in n.log() {
            match e {
                HostEvent::Rx(f) | HostEvent::TxDone(f) => dump.push(candump_of(*t, i, f)),
                _ => {}
            }
        }
        for (_, l) in n.trace() {
            let t_ns: u64 = l.split_whitespace().next().and_then(|x| x.parse().ok()).unwrap_or(0);
            trace.push((t_ns, i, l.clone()));
        }
        result.nodes.push(NodeSummary {
            name: n.name().to_string(),
            sent: n.sent().len(),
            received: n.received().len(),
            errors: n.errors(),
            tec: n.tec(),
            rec: n.rec(),
            state: n.state(),
            pending: n.pending(),
        });
    }
    dump.sort_by_key(|d| (d.0, d.1));
    result.candump = dump.into_iter().map(|d| d.2).collect();
    trace.sort_by_key(|d| (d.0, d.1));
    if opts.trace {
        result.trace.push(canstar_controller::trace::HEADER.to_string());
        result.trace.extend(trace.into_iter().map(|d| d.2));
    }
    Ok(result)
}
