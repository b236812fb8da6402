//! The stuffbit program (conformance-tests.md §11) on the bit-level harness:
//! frame sets chosen with the frame builder to cover stuff bits of both
//! levels inside and after every stuffed field, each followed by either
//! level; received from a scripted transmitter (all r0 and r1/r0 levels) and
//! sent by the RTL. Every frame is delivered, no error, counters 0.
mod common;
use canstar_controller::frame::{bus_bits, BuildOptions};
use canstar_controller::fsm::*;
use common::stim::{choose_stuffbit, STUFFBIT_RX_OPTIONS};
use common::*;

#[test]
fn stuffbit_rx_and_tx() {
    let d = BuildOptions::default();
    let (rx_frames, rx_cov, rx_all) = choose_stuffbit(11, &STUFFBIT_RX_OPTIONS, 1);
    let (tx_frames, tx_cov, tx_all) = choose_stuffbit(8, &[d], 2);
    eprintln!("stuffbit coverage: rx {}/{} cases, tx {}/{}", rx_cov.len(), rx_all.len(), tx_cov.len(), tx_all.len());
    eprintln!("stuffbit frames: rx {}, tx {} (the manual uses 11 and 8)", rx_frames.len(), tx_frames.len());
    assert_eq!(rx_cov, rx_all);
    assert_eq!(tx_cov, tx_all);
    assert!(rx_frames.len() <= 40 && tx_frames.len() <= 40);
    // every stuffed field has stuff bits of both levels, inside and after
    for field in [Field::Ident, Field::ExIdent, Field::Data, Field::Crc] {
        for level in [false, true] {
            for after_last in [false, true] {
                assert!(
                    rx_cov.iter().any(|c| c.field == field.code() as u8 && c.level == level && c.after_last == after_last),
                    "rx: {field:?} level {level} after_last {after_last}"
                );
            }
        }
    }
    // rx: a scripted N2, N1 receives
    let mut b = Bus::integrated(1);
    for (f, o) in &rx_frames {
        b.script.extend(bus_bits(f, *o, false).iter().map(|x| x.level));
        b.run(200);
        assert_eq!(b.rx[0].last(), Some(f));
    }
    assert_eq!(b.rx[0].len(), rx_frames.len());
    // tx: N1 sends, N2 receives
    let mut b = Bus::integrated(2);
    for (f, _) in &tx_frames {
        b.request(0, f);
        b.run_until(400, |b| b.nodes[0].tx_done.val());
        b.withdraw(0);
        b.run_idle(50);
        b.step();
        assert_eq!(b.rx[1].last(), Some(f));
    }
    for i in 0..2 {
        assert_eq!((b.tec(i), b.rec(i)), (0, 0));
        assert!(b.log[i].iter().all(|x| !x.has(EV_AEF) && !x.has(EV_PEF)));
    }
}
