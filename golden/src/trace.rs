//! Per-bit trace records of can-protocol.md §18.
//!
//! [`trace_line`] writes one bit record in the documented column layout:
//!
//! ```text
//! # t_ns   node field             pos stf smp drv tec rec st event
//!  24800   G1   Tx_Identifier       8  -   0   0    8   0 EA -
//! ```
//!
//! [`msg_line`] and [`req_line`] write the `MSG` and `REQ` record kinds. Data bytes of a `MSG`
//! record are written as two lowercase hex digits each, without separator (`data=` with
//! nothing after it for no data).

use super::{Frame, ReqStatus, StepOut};

/// Header line of a trace file.
pub const HEADER: &str = "# t_ns   node field             pos stf smp drv tec rec st event";

/// One bit record for the bit processed in `out`, sampled at `t_ns`.
pub fn trace_line(t_ns: u64, node: &str, out: &StepOut) -> String {
    let l = &out.label;
    let events = if out.events.is_empty() {
        "-".to_string()
    } else {
        out.events.iter().map(|e| e.token()).collect::<Vec<_>>().join(",")
    };
    format!(
        "{:>6}   {:<4} {:<18}{:>3}  {}{:>4}{:>4}{:>5}{:>4} {} {}",
        t_ns,
        node,
        l.field_name(),
        l.pos,
        if l.stuff { 'S' } else { '-' },
        out.sampled as u8,
        out.drove as u8,
        out.tec,
        out.rec,
        out.state.token(),
        events
    )
}

/// `<t_ns> <node> MSG std|ext data|remote id=0x.. dlc=n data=..`
pub fn msg_line(t_ns: u64, node: &str, f: &Frame) -> String {
    let data: String = f.data.iter().map(|b| format!("{b:02x}")).collect();
    format!(
        "{:>6}   {:<4} MSG {} {} id=0x{:x} dlc={} data={}",
        t_ns,
        node,
        if f.ide { "ext" } else { "std" },
        if f.rtr { "remote" } else { "data" },
        f.id,
        f.dlc,
        data
    )
}

/// `<t_ns> <node> REQ pending|transmitting|done|error`
pub fn req_line(t_ns: u64, node: &str, st: ReqStatus) -> String {
    let s = match st {
        ReqStatus::None => "none",
        ReqStatus::Pending => "pending",
        ReqStatus::Transmitting => "transmitting",
        ReqStatus::Done => "done",
        ReqStatus::Error => "error",
    };
    format!("{:>6}   {:<4} REQ {}", t_ns, node, s)
}

/// All records of one step of one node: the bit record, then `MSG` and `REQ` if any.
pub fn step_lines(t_ns: u64, node: &str, out: &StepOut) -> Vec<String> {
    let mut v = vec![trace_line(t_ns, node, out)];
    if let Some(f) = out.delivered() {
        v.push(msg_line(t_ns, node, f));
    }
    for &r in &out.req {
        v.push(req_line(t_ns, node, r));
    }
    v
}
