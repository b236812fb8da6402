//! dlc (§5 of the plan): data and remote frames with DLC codes 0..15,
//! received by N1 from N2 (`dlc_rx_d<k>`, `dlc_rx_r<k>`) and sent by N1 to N2
//! (`dlc_tx_d<k>`, `dlc_tx_r<k>`).
use super::*;

fn frame(k: u8, remote: bool) -> Frame {
    let data: Vec<u8> = (0..k.min(8)).map(|i| 0x11u8.wrapping_mul(i + 1) ^ (k << 4)).collect();
    if remote {
        Frame::remote(false, 0x100 + k as u32, k)
    } else {
        Frame::data(false, 0x200 + k as u32, k, &data)
    }
}

/// N `from` sends `f` to N `to`; both must end without errors, counters 0.
pub(crate) fn exchange(b: &mut Bench, from: usize, to: usize, f: &Frame) -> Result<(), String> {
    let (rx0, tx0) = (b.node(to).received().len(), b.node(from).sent().len());
    let (m_from, m_to) = (b.mark(from), b.mark(to));
    b.node_mut(from).request(f.clone());
    b.run_until(400, |b| b.node(from).sent().len() > tx0).map_err(|e| format!("N{} did not send: {e}{}", from + 1, b.dump_events(from, m_from)))?;
    b.run_idle(100)?;
    check_delivered(b, to, rx0, std::slice::from_ref(f))?;
    ensure!(b.node(from).sent()[tx0..] == [f.clone()], "N{} sent {:?}", from + 1, &b.node(from).sent()[tx0..]);
    let got = &b.node(to).received()[rx0];
    ensure!(got.dlc == f.dlc && got.data.len() == if f.rtr { 0 } else { f.dlc.min(8) as usize } && got.rtr == f.rtr, "delivered {:?}", got);
    for (i, m) in [(from, m_from), (to, m_to)] {
        let errs = b.since(i, m).iter().filter(|r| r.ev & ((1 << EV_AEF) | (1 << EV_PEF) | (1 << EV_OLF)) != 0).count();
        ensure!(errs == 0, "N{} flagged:{}", i + 1, b.dump_events(i, m));
        ensure!((b.tec(i), b.rec(i)) == (0, 0), "N{} TEC {} REC {}", i + 1, b.tec(i), b.rec(i));
    }
    Ok(())
}

pub fn run(ctx: &mut Ctx) {
    let mut b = ctx.bench(vec![cfg(), cfg()], false);
    for (part, from, to) in [("rx", 1, 0), ("tx", 0, 1)] {
        for remote in [false, true] {
            for k in 0..16u8 {
                let name = format!("dlc_{part}_{}{k}", if remote { 'r' } else { 'd' });
                let r = exchange(&mut b, from, to, &frame(k, remote));
                ctx.record(&name, r);
            }
        }
    }
}
