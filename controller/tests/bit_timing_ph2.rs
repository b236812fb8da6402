//! Every SJA1000 bus timing setting, and PH2 = 1 TQ on the wire:
//!
//! - `btr1_sweep`: every BTR1 value (TSEG1 0..15, TSEG2 0..7, SAM) at
//!   several BRP and SJW values through the RTL of `BusTiming` and the bit
//!   timing logic: a setting the core accepts gives the datasheet's bit time
//!   (2·(BRP+1)·(3 + TSEG1 + TSEG2) clocks) and sample point ((2 + TSEG1) TQ
//!   after the bit start) in clocks, measured on TX and the sample strobe;
//!   the others (TSEG1 = 0, bits under 8 TQ) raise `cfg_err` and keep TX
//!   recessive, and `core_timing` names them.
//! - `ph2_1_frames_at_two_clocks_per_tq`: two cores at the shortest legal
//!   PH2 = 1 setting (TQ = 2 clocks, so the transmit point is 2 clocks after
//!   the sample point's tick: the whole time the frame logic has, see the
//!   port contract of `canstar_hdl::btl`) exchange frames with arbitration
//!   and acknowledgement, with the sample points where the datasheet puts
//!   them.
mod common;
use canstar_controller::frame::Frame;
use canstar_controller::sja1000::timing::{core_timing, mapped, BusTiming};
use canstar_hdl::btl::{BitTiming, BtlConfig, BtlInputs};
use canstar_hdl::drive;
use common::core_bus::CoreBus;

/// The core fields `BusTiming` gives for BTR0/BTR1 (its RTL after a reset).
fn bus_timing(btr0: u8, btr1: u8) -> BtlInputs {
    let mut u = BusTiming::new(btr0, btr1);
    drive::init(&mut u);
    u.rst.next = true;
    drive::cycle(&mut u);
    let f = |x: usize| x as u32;
    BtlInputs {
        reset: false,
        brp: f(u.brp.val().index()),
        prop: f(u.prop.val().index()),
        ph1: f(u.ph1.val().index()),
        ph2: f(u.ph2.val().index()),
        sjw: f(u.sjw.val().index()),
        triple: u.triple.val(),
        rx: true,
        drive: true,
        hs_en: false,
    }
}

/// The bit timing RTL on the fields of `i`, looped back (RX = TX) and
/// driving alternately one bit D and two bits R (the new level on the clock
/// after the sample strobe, as the frame logic does): (cfg_err, clocks
/// between TX edges, clocks from each TX edge to the next sample strobe).
fn measure(i: BtlInputs, bits: usize) -> (bool, Vec<usize>, Vec<usize>) {
    let mut u = BitTiming::default();
    drive::init(&mut u);
    let mut i = BtlInputs { reset: true, ..i };
    u.set_inputs(&i);
    drive::cycle(&mut u);
    drive::cycle(&mut u);
    i.reset = false;
    let (mut edges, mut widths, mut offsets) = (vec![], vec![], vec![]);
    let (mut prev_tx, mut n, mut cycle) = (true, 0usize, 0usize);
    let limit = if bits == 0 { 600 } else { 2 * 128 * 25 * (bits + 2) };
    while (bits == 0 || offsets.len() < bits) && cycle < limit {
        i.rx = u.tx.val();
        u.set_inputs(&i);
        drive::settle(&mut u);
        if u.sample.val() {
            n += 1;
            if let Some(&e) = edges.last() {
                offsets.push(cycle - e);
            }
            // the frame logic's decision, from the next clock on
            i.drive = n % 3 != 0;
        }
        if u.tx.val() != prev_tx {
            if let Some(&e) = edges.last() {
                widths.push(cycle - e);
            }
            edges.push(cycle);
            prev_tx = u.tx.val();
        }
        drive::rising_edge(&mut u);
        drive::falling_edge(&mut u);
        cycle += 1;
    }
    (u.cfg_err.val(), widths, offsets)
}

#[test]
fn btr1_sweep() {
    let mut accepted = 0;
    for btr0 in [0x00u8, 0x01, 0x45, 0xC0] {
        for btr1 in 0..=255u8 {
            let i = bus_timing(btr0, btr1);
            let tag = format!("BTR0/BTR1 0x{btr0:02X}/0x{btr1:02X}");
            let (t1, t2) = ((btr1 & 15) as usize + 1, ((btr1 >> 4) & 7) as usize + 1);
            let tq = 2 * ((btr0 & 63) as usize + 1);
            let cfg = BtlConfig::from_fields(i.brp, i.prop, i.ph1, i.ph2, i.sjw, i.triple);
            assert_eq!(cfg, mapped(btr0, btr1), "{tag}");
            let refused = t1 == 1 || 1 + t1 + t2 < 8;
            let (cfg_err, widths, offsets) = measure(i, if refused { 0 } else { 9 });
            assert_eq!(cfg_err, refused, "{tag}: cfg_err");
            if refused {
                assert!(widths.is_empty(), "{tag}: TX must stay recessive");
                assert!(core_timing(btr0, btr1).unwrap_err().contains(&format!("0x{btr1:02X}")));
                continue;
            }
            accepted += 1;
            let bit = tq * (1 + t1 + t2);
            // bits of D, R, R: TX edges 1 and 2 bits apart, the sample point
            // (1 + t1) TQ after each bit start
            assert!(widths.iter().all(|&w| w == bit || w == 2 * bit), "{tag}: bit {bit} clocks, TX edges {widths:?}");
            assert!(widths.contains(&bit) && widths.contains(&(2 * bit)), "{tag}: {widths:?}");
            assert!(
                offsets.iter().all(|&o| o % bit == (1 + t1) * tq),
                "{tag}: sample point {} clocks, {offsets:?}",
                (1 + t1) * tq
            );
            // the SJW limit (PH1 = t1 - 1) is the only difference from the datasheet
            let sjw = (btr0 >> 6) as usize + 1;
            assert_eq!(core_timing(btr0, btr1).is_ok(), sjw < t1, "{tag}");
        }
    }
    // per BTR0: 15 TSEG1 > 0 times 8 TSEG2, less the 10 under 8 TQ, with and without SAM
    assert_eq!(accepted, 4 * 2 * (15 * 8 - 10), "settings of 8..25 TQ with TSEG1 > 0");
}

/// Sample strobes relative to the latest change of the bus level, per node:
/// (clocks since the edge, whether the node's own TX made the edge), for the
/// samples in the first bit after an edge.
struct Phase {
    last_edge: usize,
    own: [bool; 2],
    bus: bool,
    tx: [bool; 2],
    offsets: [Vec<(usize, bool)>; 2],
}

#[test]
fn ph2_1_frames_at_two_clocks_per_tq() {
    // 8 TQ of 2 clocks, SP after 7 TQ (87.5 %), PH2 = 1: 16 clocks per bit,
    // the sample point 14 clocks after the bit start
    let cfg = BtlConfig::new(2, 1, 5, 1).with_ph2(1);
    assert!(cfg.is_valid());
    let (bit, sp) = (16usize, 14usize);
    let mut b = CoreBus::with_config(2, &[0, 0], &cfg);
    b.run(13 * bit);
    let mut ph = Phase { last_edge: 0, own: [false; 2], bus: true, tx: [true; 2], offsets: [vec![], vec![]] };
    let frames =
        [Frame::std(0x123, &[0x55, 0xAA]), Frame::std(0x124, &[]), Frame::ext(0x1ABCDEF, &[1, 2, 3, 4, 5, 6, 7, 8])];
    let mut sent = 0;
    let mut want = vec![vec![], vec![]];
    for (k, f) in frames.iter().enumerate() {
        // node 0 sends every frame; node 1 sends one more at the same time
        // (arbitration: the lower identifier wins, the other retries)
        b.request(0, f);
        let other = Frame::std(0x200 + k as u32, &[k as u8]);
        if k == 1 {
            b.request(1, &other);
            want[0].push(other.clone());
        }
        want[1].push(f.clone());
        let mut pending = [true, k == 1];
        let start = b.cycle;
        while pending.iter().any(|&p| p) {
            // a strobe shows the sample of the tick before: measure it from
            // the edge before this clock's
            for i in 0..2 {
                if b.nodes[i].dbg_sample.val() && b.cycle - ph.last_edge <= bit {
                    ph.offsets[i].push((b.cycle - ph.last_edge, ph.own[i]));
                }
            }
            let bus = b.bus();
            let tx = [b.nodes[0].tx.val(), b.nodes[1].tx.val()];
            if bus != ph.bus {
                ph.bus = bus;
                ph.last_edge = b.cycle;
                ph.own = [tx[0] != ph.tx[0], tx[1] != ph.tx[1]];
            }
            ph.tx = tx;
            for i in 0..2 {
                assert!(!b.nodes[i].error.val(), "node {i}: error at cycle {}", b.cycle);
                if b.nodes[i].tx_done.val() && pending[i] {
                    pending[i] = false;
                    b.withdraw(i);
                    sent += 1;
                }
            }
            b.step();
            assert!(b.cycle - start < 400 * bit, "frame {k} not done");
        }
        b.run(12 * bit);
    }
    assert_eq!(sent, 4);
    assert_eq!(b.rx, want, "frames received");
    assert_eq!((b.tec(0), b.rec(0), b.tec(1), b.rec(1)), (0, 0, 0, 0));
    // Each node samples (1 + t1) TQ = 14 clocks after the start of a bit
    // that begins with an edge: exactly, on its own TX edge (transmitter),
    // and 1 or 2 clocks later on another node's edge (its synchroniser,
    // then the TQ grid), or 2 clocks (one TQ of PH1 lengthening, SJW 1)
    // earlier than that when it resynchronised on the edge (a transmitter
    // seeing a receiver's ACK).
    for i in 0..2 {
        let o = &ph.offsets[i];
        assert!(o.iter().filter(|x| x.1).all(|x| x.0 == sp), "node {i}: on its own edges {o:?}");
        assert!(o.iter().filter(|x| !x.1).all(|x| (sp..=sp + 2).contains(&x.0)), "node {i}: on other edges {o:?}");
        assert!(o.iter().any(|x| x.1) && o.iter().any(|x| !x.1 && x.0 > sp), "node {i}: {o:?}");
    }
}
