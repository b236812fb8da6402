//! Starting a fault of a run: which nets it disturbs and which controllers it
//! makes unhealthy.

use canstar_controller::fsm::Field;
use canstar_sim::net::{FaultMode, NetId};
use canstar_sim::Sim;

use crate::driver::Driver;
use crate::fault::{CtrlRef, Dir, FaultKind, FaultSpec, FaultTarget, StartField};
use crate::network::Network;

/// What a started fault affects.
pub(super) struct Active {
    /// (node, ctrl) made unhealthy by this fault (their links, their crash, their hub).
    pub unhealthy: Vec<(usize, usize)>,
}

/// Field codes of the controller for a start field.
pub(super) fn ctrl_field(f: StartField) -> Field {
    match f {
        StartField::Sof => Field::Sof,
        StartField::Ident => Field::Ident,
        StartField::Dlc => Field::Dlc,
        StartField::Data => Field::Data,
        StartField::Crc => Field::Crc,
        StartField::AckSlot => Field::AckSlot,
        StartField::Eof => Field::Eof,
        StartField::Inter => Field::Inter,
    }
}

fn mode_of(k: FaultKind) -> FaultMode {
    match k {
        FaultKind::Sad => FaultMode::StuckDominant,
        FaultKind::Sar => FaultMode::StuckRecessive,
        FaultKind::Invert => FaultMode::Invert,
        FaultKind::BitFlip { .. } | FaultKind::Force { .. } | FaultKind::Burst { .. } => FaultMode::None,
    }
}

/// Start fault `f` at time `t >= now`; describe it in `desc`.
#[allow(clippy::too_many_arguments)]
pub(super) fn inject(sim: &mut Sim, net: &Network, drivers: &[Driver], f: &FaultSpec, t: u64, bit: u64, limit: u64, desc: &mut String) -> Active {
    let resolve = |node: usize, r: CtrlRef| -> usize {
        let tx = drivers[node].tx.unwrap_or(0);
        match r {
            CtrlRef::A => 0,
            CtrlRef::B => 1,
            CtrlRef::Tx => tx,
            CtrlRef::NonTx => 1 - tx,
        }
    };
    let role = |node: usize, c: usize| if drivers[node].tx == Some(c) { "tx" } else { "non-tx" };
    let mut nets: Vec<NetId> = Vec::new();
    let mut unhealthy = Vec::new();
    match f.target {
        FaultTarget::Link { node, ctrl, dir } => {
            let c = resolve(node, ctrl);
            let hp = &net.links.hubs[c];
            nets.push(match dir {
                Dir::Up => hp.uplinks[node].output,
                Dir::Down => hp.downlinks[node].output,
            });
            unhealthy.push((node, c));
            *desc = format!("node {node} ctrl {} ({}) {:?}link {:?}", "AB".as_bytes()[c] as char, role(node, c), dir, f.kind);
        }
        FaultTarget::Sublink { interlink, from_hub } => {
            nets.push(net.links.hubs[from_hub].sub_out[interlink].output);
            *desc = format!("interlink {interlink} sublink from hub {from_hub} {:?}", f.kind);
        }
        FaultTarget::Interlink { interlink } => {
            nets.push(net.links.hubs[0].sub_out[interlink].output);
            nets.push(net.links.hubs[1].sub_out[interlink].output);
            *desc = format!("interlink {interlink} {:?}", f.kind);
        }
        FaultTarget::Hub { hub } => {
            let hp = &net.links.hubs[hub];
            nets.extend(hp.downlinks.iter().map(|l| l.output));
            nets.extend(hp.sub_out.iter().map(|l| l.output));
            unhealthy.extend((0..net.ctrls.len()).map(|k| (k, hub)));
            *desc = format!("hub {hub} output {:?}", f.kind);
        }
        FaultTarget::Crash { node, ctrl } => {
            let c = resolve(node, ctrl);
            *desc = format!("node {node} ctrl {} ({}) crash", "AB".as_bytes()[c] as char, role(node, c));
            // the crash is immediate (at the slice boundary)
            sim.get_mut(net.ctrls[node][c]).crash();
            return Active { unhealthy: vec![(node, c)] };
        }
    }
    let end = f.duration_ps.map(|d| t + d);
    for &id in &nets {
        if !crate::fault::schedule_pattern(sim, id, f.kind, t, end.unwrap_or(limit + bit), bit) {
            sim.schedule_fault(id, t, mode_of(f.kind));
            if let Some(e) = end {
                sim.schedule_fault(id, e, FaultMode::None);
            }
        }
    }
    Active { unhealthy }
}
