//! Running a scenario on the RTL controller.

use super::{candump_line, FrameSpec, NodeMode, Scenario};
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
    /// Stop at this simulated time (ps) if it comes before the scenario's
    /// `duration_us` (`canstar sim --ms`).
    pub until_ps: Option<u64>,
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
    let end = (s.duration_us * 1_000_000).min(opts.until_ps.unwrap_or(u64::MAX));
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
                    let start = (last_sample[a.node] + bt.ph2 as u64 * tq_ps[a.node]).max(t);
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
