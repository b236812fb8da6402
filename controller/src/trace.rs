//! Per-bit trace records (§18 of can-protocol.md) from the debug bundle of a
//! [`CanCore`].
//!
//! [`BitTracer::clock`] is called once per clock, after the clock edge, with
//! the time of that clock. On the clock where `dbg_sample` is high it latches
//! FIELD, POSITION, stuff marker, role, the sampled level and the TX level;
//! on the next clock (event word with `EV_BIT`) it completes the record with
//! the events and the counters after processing, and returns the line.

use crate::view::CoreView;
use crate::frame::Frame;
use crate::fsm::*;

#[derive(Clone, Copy, Debug)]
struct Pending {
    t_ns: u64,
    field: Field,
    pos: u64,
    stuff: bool,
    role_tx: bool,
    smp: bool,
    drv: bool,
}

/// Builds §18 trace lines for one node.
#[derive(Clone, Debug)]
pub struct BitTracer {
    node: String,
    pending: Option<Pending>,
    state: u64,
    warn: bool,
    daf: u64,
}

/// The §18 column header.
pub const HEADER: &str = "# t_ns   node field                 pos stf smp drv  tec rec st event";

impl BitTracer {
    /// A tracer for the node labelled `node` (e.g. `D1`).
    pub fn new(node: &str) -> Self {
        BitTracer { node: node.to_string(), pending: None, state: 0, warn: false, daf: 0 }
    }

    /// Look at the core after a clock edge; returns the completed lines
    /// (a bit record and/or a `MSG` record).
    pub fn clock(&mut self, t_ns: u64, c: &(impl CoreView + ?Sized)) -> Vec<String> {
        let mut out = Vec::new();
        let ev = c.dbg_events() as u64;
        let has = |b: usize| (ev >> b) & 1 == 1;
        if has(EV_BIT) {
            if let Some(p) = self.pending.take() {
                let tec = c.tec() as u64;
                let rec = c.rec() as u64;
                let st = c.state() as u64;
                let warn = c.err_warn();
                let mut tok: Vec<String> = Vec::new();
                let names = [
                    (EV_SOF, "SOF"),
                    (EV_ARB_LOST, "ARB_LOST"),
                    (EV_BIT_ERR, "BIT_ERR"),
                    (EV_STUFF_ERR, "STUFF_ERR"),
                    (EV_CRC_ERR, "CRC_ERR"),
                    (EV_FORM_ERR, "FORM_ERR"),
                    (EV_ACK_ERR, "ACK_ERR"),
                    (EV_AEF, "AEF"),
                    (EV_PEF, "PEF"),
                    (EV_OLF, "OLF"),
                    (EV_OVL, "OVL"),
                ];
                for (b, n) in names {
                    if has(b) {
                        tok.push(n.to_string());
                    }
                }
                if has(EV_DAF) {
                    self.daf += 1;
                    tok.push(format!("DAF={}", self.daf));
                } else {
                    self.daf = 0;
                }
                for (b, n) in [(EV_TX_OK, "TX_OK"), (EV_RX_OK, "RX_OK"), (EV_EXC1, "EXC1"), (EV_EXC2, "EXC2")] {
                    if has(b) {
                        tok.push(n.to_string());
                    }
                }
                if st != self.state {
                    tok.push(["TO_EA", "TO_EP", "TO_BO", "TO_BO"][st as usize & 3].to_string());
                    self.state = st;
                }
                if has(EV_RUN) {
                    // the run counter is cleared by the recovery itself
                    let k = if has(EV_RECOVERED) { 128 } else { c.dbg_runs() };
                    tok.push(format!("RUN={k}"));
                }
                if has(EV_RECOVERED) {
                    tok.push("RECOVERED".to_string());
                }
                if warn != self.warn {
                    tok.push(if warn { "WARN" } else { "WARN_CLR" }.to_string());
                    self.warn = warn;
                }
                let field = if p.field.has_role() {
                    format!("{}{}", if p.role_tx { "Tx_" } else { "Rx_" }, p.field.name())
                } else {
                    p.field.name().to_string()
                };
                out.push(format!(
                    "{:>7}   {:<4} {:<22} {:>3}  {}   {}   {} {:>4} {:>3} {} {}",
                    p.t_ns,
                    self.node,
                    field,
                    p.pos,
                    if p.stuff { "S" } else { "-" },
                    p.smp as u8,
                    p.drv as u8,
                    tec,
                    rec,
                    ["EA", "EP", "BO", "BO"][st as usize & 3],
                    if tok.is_empty() { "-".to_string() } else { tok.join(",") }
                ));
            }
        }
        if c.rx_valid() {
            let f = c.rx_frame();
            out.push(msg_line(t_ns, &self.node, &f));
        }
        if c.dbg_sample() {
            self.pending = Some(Pending {
                t_ns,
                field: Field::from_code(c.dbg_field() as u64).unwrap_or(Field::Reset),
                pos: c.dbg_pos() as u64,
                stuff: c.dbg_stuff(),
                role_tx: c.dbg_role(),
                smp: c.dbg_busmon(),
                drv: c.tx(),
            });
        }
        out
    }
}

/// The `MSG` record of a delivered frame (§18).
pub fn msg_line(t_ns: u64, node: &str, f: &Frame) -> String {
    let data: Vec<String> = f.data.iter().map(|b| format!("{b:02x}")).collect();
    format!(
        "{:>7}   {:<4} MSG {} {} id=0x{:x} dlc={} data={}",
        t_ns,
        node,
        if f.ide { "ext" } else { "std" },
        if f.rtr { "remote" } else { "data" },
        f.id,
        f.dlc,
        if data.is_empty() { "-".to_string() } else { data.join("") }
    )
}
