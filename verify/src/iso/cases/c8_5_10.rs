//! ISO 16845-1:2016 clause 8.5.10 — an error-passive transmitter reaches
//! bus-off and then ignores the bus.
//!
//! What the case checks (in our words): the IUT starts at TEC 0 and
//! transmits a base-format data frame; the LT overwrites its first
//! recessive data bit with a dominant one (bit error, TEC 8) and forces the
//! bus recessive during 16 bits of the IUT's active error flag (16 bit
//! errors, TEC 136; the flag after the 16th is passive, see 8.5.15). After
//! the passive error flag (six recessive bits) the LT drives 112 dominant
//! bits: every 8th adds 8 (TEC 248). After error delimiter, intermission
//! and suspend the IUT repeats its frame, which the LT acknowledges and
//! checks bit by bit (TEC 247), and the LT drives the first intermission
//! bit dominant. The IUT's overload flag starts; the LT forces its first
//! bit recessive (bit error, TEC 255, a passive error flag). 6 + 7 bits
//! later the LT drives the last error delimiter bit dominant; the IUT's
//! new overload flag starts and the LT forces its first bit recessive
//! again: TEC 263, bus-off. 6 + 8 + 3 + 8 bit times later the LT sends a
//! valid frame: the bus-off IUT must stay recessive (no ACK) and deliver
//! nothing. The frame was transmitted once; after the bus-off recovery
//! (128 × 11 recessive bits, automatic in canstar) TEC and REC are 0.
//!
//! Elementary test: `iso_8_5_10_bus_off_from_passive`.

use super::super::LtBench;
use super::c8_5_2::{bit_error_first, lt_frame, passive_tx, Scenario};
use crate::conformance::{ensure, Ctx, StepResult};
use crate::node::NodeConfig;
use canstar_controller::fsm::*;

pub fn run() -> Vec<StepResult> {
    let mut ctx = Ctx { program: "iso_8_5_10".into(), vcd: None, results: vec![] };
    let mut lb = LtBench::new(vec![NodeConfig::named("iut")]);
    let r = (|| {
        let mut v = vec![true; 16 + 6];
        v.extend([false; 112]);
        v.extend([true; 8 + 3 + 8]);
        let mut t = vec![false, true];
        t.extend([true; 6 + 7]);
        t.extend([false, true]);
        t.extend([true; 6 + 8 + 3 + 8]);
        let s = Scenario {
            tec0: 0,
            levels: v,
            forced: (0..16).collect(),
            iut_dom: (0..16).collect(),
            tail: Some(t),
            tail_forced: vec![1, 16],
            tail_dom: vec![1, 16],
            tail_frame: Some(lt_frame()),
            idle_bits: 1408 + 200,
            ..Default::default()
        };
        let o = passive_tx(&mut lb, &s)?;
        bit_error_first(&o, 8, 19)?;
        let bits = o.r.iut_events(EV_BIT_ERR);
        ensure!(bits.len() == 19, "{} bit errors:{}", bits.len(), o.r.dump(0));
        ensure!(bits[16].tec == 136 && bits[16].has(EV_PEF), "after the 16th flag bit error: {}", bits[16]);
        let b = bits[17];
        ensure!(b.field == Field::OvlFlag && b.pos == 1 && b.tec == 255 && b.has(EV_PEF), "first overload flag bit error: {b}");
        let b = bits[18];
        ensure!(b.field == Field::OvlFlag && b.pos == 1 && b.tec == 263 && b.state == 2, "second overload flag bit error: {b}");
        let ok = o.r.iut_events(EV_TX_OK);
        ensure!(ok.len() == 1 && ok[0].tec == 247, "success: {ok:?}");
        ensure!(o.r.iut_events(EV_RECOVERED).len() == 1, "no bus-off recovery:{}", o.r.dump(0));
        ensure!(lb.b.tec(0) == 0 && lb.b.rec(0) == 0 && lb.b.state(0) == 0, "TEC {} REC {} state {} after the recovery", lb.b.tec(0), lb.b.rec(0), lb.b.state(0));
        Ok(())
    })();
    ctx.record("iso_8_5_10_bus_off_from_passive", r);
    ctx.results
}
