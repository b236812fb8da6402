//! The extd_id program (conformance-tests.md §7) on the bit-level harness.
//! Frames the RTL never sends (dominant SRR, recessive r0) come from a
//! scripted transmitter (levels from the frame builder wired-AND into the bus).
mod common;
use canstar_controller::frame::{bus_bits, BuildOptions, Frame};
use canstar_controller::fsm::*;
use common::*;

fn levels(f: &Frame, o: BuildOptions) -> Vec<bool> {
    // the scripted node leaves the ACK slot recessive (the receiver acknowledges)
    bus_bits(f, o, false).iter().map(|b| b.level).collect()
}

const STD: BuildOptions = BuildOptions { srr: true, r1: false, r0: false };

#[test]
fn extd_id_rx() {
    let r0r = BuildOptions { r0: true, ..STD };
    let srr_d = BuildOptions { srr: false, ..STD };
    let cases = [
        ("rx_1", Frame::remote(false, 0x28F, 0), STD),
        ("rx_2", Frame::remote(false, 0x28F, 0), r0r),
        ("rx_3", Frame::std(0x290, &[]), STD),
        ("rx_4", Frame::std(0x290, &[]), r0r),
        ("rx_5", Frame::std(0x288, &[]), STD),
        ("rx_6", Frame::ext(0x0A0CA5A5, &[]), STD),
        ("rx_7", Frame::ext(0x0A3CA5A5, &[]), STD),
        ("rx_8", Frame::ext(0x0A3EA5A5, &[]), STD),
        ("rx_9", Frame::ext(0x0A40A5A5, &[]), srr_d),
        ("rx_10", Frame::ext(0x0A42A5A5, &[]), srr_d),
    ];
    let mut b = Bus::integrated(1);
    for (name, f, o) in cases {
        b.script.extend(levels(&f, o));
        b.run(120);
        assert_eq!(b.rx[0].last(), Some(&f), "{name}");
        assert_eq!((b.tec(0), b.rec(0)), (0, 0), "{name}");
    }
    assert!(b.log[0].iter().all(|x| !x.has(EV_AEF)));
    assert_eq!(b.rx[0].len(), 10);
}

#[test]
fn extd_id_tx() {
    let frames = [
        Frame::remote(false, 0x28F, 0),
        Frame::std(0x290, &[]),
        Frame::std(0x288, &[]),
        Frame::ext(0x0A0CA5A5, &[]),
        Frame::ext(0x0A3CA5A5, &[]),
        Frame::ext(0x0A3EA5A5, &[]),
    ];
    let mut b = Bus::integrated(2);
    for f in &frames {
        b.request(0, f);
        b.run_until(300, |b| b.nodes[0].tx_done.val());
        b.withdraw(0);
        b.run_idle(50);
        b.step();
        assert_eq!(b.rx[1].last(), Some(f));
    }
    assert_eq!((b.tec(0), b.rec(1)), (0, 0));
}

#[test]
fn extd_id_arb() {
    let x = 0x2A5u32;
    let e = 0x2_5A5A;
    // (name, N1 frame, N2 frame, N2 scripted options or None for an RTL N2, loss field)
    let cases: Vec<(&str, Frame, Frame, Option<BuildOptions>, Field)> = vec![
        ("arb_1", Frame::remote(false, x, 1), Frame::std(x, &[1]), None, Field::Rtr),
        ("arb_2", Frame::remote(false, x, 1), Frame::ext(x << 18 | e, &[2]), Some(BuildOptions { srr: false, ..STD }), Field::Rtr),
        ("arb_3", Frame::ext(x << 18 | e, &[3]), Frame::std(x, &[3]), None, Field::Srr),
        ("arb_4", Frame::ext(x << 18 | e, &[4]), Frame::remote(false, x, 4), None, Field::Ide),
        ("arb_5", Frame::ext(x << 18 | e, &[5]), Frame::ext(x << 18 | (e - 0x100), &[5]), None, Field::ExIdent),
        ("arb_6", Frame::remote(true, x << 18 | e, 6), Frame::ext(x << 18 | e, &[6]), None, Field::Rtr),
        ("arb_7", Frame::ext(x << 18 | e, &[7]), Frame::ext(x << 18 | e, &[7, 7]), Some(BuildOptions { srr: false, ..STD }), Field::Srr),
    ];
    for (name, f1, f2, scripted, loss) in cases {
        let mut b = Bus::integrated(2);
        b.request(0, &f1);
        if let Some(o) = scripted {
            // N2 is a script starting in the same bit as N1's SOF
            b.run_to(0, Field::Sof, 1, 20);
            b.script.extend(levels(&f2, o));
        } else {
            b.request(1, &f2);
        }
        let s = b.bit;
        b.run_until(400, |b| !b.events(0, EV_ARB_LOST, s).is_empty());
        let l = b.events(0, EV_ARB_LOST, s)[0].clone();
        assert_eq!(l.field, loss, "{name}: {l:?}");
        b.step();
        assert!(b.last(0).drv, "{name}: recessive after the loss");
        b.run_until(400, |b| b.rx[0].last() == Some(&f2));
        if scripted.is_none() {
            b.run_until(10, |b| !b.events(1, EV_TX_OK, s).is_empty());
            b.withdraw(1);
        }
        // N1 retries and succeeds
        b.run_until(400, |b| b.nodes[0].tx_done.val());
        b.withdraw(0);
        b.run_idle(50);
        if scripted.is_none() {
            assert_eq!(b.rx[1].last(), Some(&f1), "{name}");
        }
        for i in 0..2 {
            assert_eq!((b.tec(i), b.rec(i)), (0, 0), "{name} node {i}");
        }
    }
}
