//! Acceptance filtering, single and dual filter mode, standard and
//! extended identifiers, against an independent reference of the data
//! sheet's filter rules.
mod sja1000_util;
use canstar_controller::frame::Frame;
use canstar_controller::sja1000::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use sja1000_util::*;

/// (code, mask) bit-by-bit match: mask bit 1 = don't care.
fn m(code: u8, mask: u8, v: u8, bits: u8) -> bool {
    // compare only `bits` (a bit set selects a compared position)
    ((code ^ v) & !mask & bits) == 0
}

/// The data sheet's acceptance filter (reference, written from the tables).
fn accept(afm: bool, acr: [u8; 4], amr: [u8; 4], f: &Frame) -> bool {
    let id = f.id;
    let rtr = f.rtr as u8;
    let d0 = if f.data.is_empty() { None } else { Some(f.data[0]) };
    let d1 = if f.data.len() < 2 { None } else { Some(f.data[1]) };
    if afm {
        if f.ide {
            m(acr[0], amr[0], (id >> 21) as u8, 0xFF)
                && m(acr[1], amr[1], (id >> 13) as u8, 0xFF)
                && m(acr[2], amr[2], (id >> 5) as u8, 0xFF)
                && m(acr[3], amr[3], ((id as u8) << 3) | (rtr << 2), 0xFC)
        } else {
            m(acr[0], amr[0], (id >> 3) as u8, 0xFF)
                && m(acr[1], amr[1], ((id as u8) << 5) | (rtr << 4), 0xF0)
                && d0.is_none_or(|d| m(acr[2], amr[2], d, 0xFF))
                && d1.is_none_or(|d| m(acr[3], amr[3], d, 0xFF))
        }
    } else if f.ide {
        let f1 = m(acr[0], amr[0], (id >> 21) as u8, 0xFF) && m(acr[1], amr[1], (id >> 13) as u8, 0xFF);
        let f2 = m(acr[2], amr[2], (id >> 21) as u8, 0xFF) && m(acr[3], amr[3], (id >> 13) as u8, 0xFF);
        f1 || f2
    } else {
        let f1 = m(acr[0], amr[0], (id >> 3) as u8, 0xFF)
            && m(acr[1], amr[1], ((id as u8) << 5) | (rtr << 4), 0xF0)
            && d0.is_none_or(|d| m(acr[1], amr[1], d >> 4, 0x0F) && m(acr[3], amr[3], d & 0x0F, 0x0F));
        let f2 = m(acr[2], amr[2], (id >> 3) as u8, 0xFF) && m(acr[3], amr[3], ((id as u8) << 5) | (rtr << 4), 0xF0);
        f1 || f2
    }
}

fn run_filter(afm: bool, seed: u64) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut n = Net::opened(2, CtrlMode::default());
    let mut accepted_any = 0;
    let mut rejected_any = 0;
    for round in 0..4 {
        let acr: [u8; 4] = rng.gen();
        // masks with few don't-care bits so that both outcomes occur
        let amr: [u8; 4] = [0, 1, 2, 3].map(|_| {
            let mut v = 0u8;
            for b in 0..8 {
                if rng.gen_bool(0.3) {
                    v |= 1 << b;
                }
            }
            v
        });
        n.set_reset_mode(1);
        for k in 0..4 {
            n.wr(1, REG_ACCC0 + k as u8, acr[k]);
            n.wr(1, REG_ACCM0 + k as u8, amr[k]);
        }
        n.wr(1, REG_MOD, if afm { MOD_AFM } else { 0 });
        assert_eq!(n.rd(1, REG_MOD), if afm { MOD_AFM } else { 0 });
        n.wr(1, REG_IER, !IRQ_BEI);
        n.run(13 * BIT);
        let before = n.drv[1].rx.len();
        let mut exp = vec![];
        for k in 0..10 {
            // frames built from the code with random flips of a few bits
            let ide = k % 2 == 1;
            let rtr = rng.gen_bool(0.2);
            let flip = |rng: &mut ChaCha8Rng, v: u8| if rng.gen_bool(0.5) { v } else { v ^ (1 << rng.gen_range(0..8)) };
            let id = if ide {
                let (c0, c1, c2, c3) = if afm || rng.gen_bool(0.5) { (acr[0], acr[1], acr[2], acr[3]) } else { (acr[2], acr[3], rng.gen(), rng.gen()) };
                ((flip(&mut rng, c0) as u32) << 21) | ((flip(&mut rng, c1) as u32) << 13) | ((c2 as u32) << 5) | ((c3 as u32) >> 3)
            } else {
                let (c0, c1) = if afm || rng.gen_bool(0.5) { (acr[0], acr[1]) } else { (acr[2], acr[3]) };
                ((flip(&mut rng, c0) as u32) << 3) | ((c1 as u32) >> 5)
            };
            let dlc = rng.gen_range(0..4u8);
            let d0 = if afm { acr[2] } else { (acr[1] << 4) | (acr[3] & 15) };
            let data = [flip(&mut rng, d0), flip(&mut rng, acr[3]), 0, 0];
            let f = if rtr { Frame::remote(ide, id & if ide { 0x1FFF_FFFF } else { 0x7FF }, dlc) } else { Frame::data(ide, id & if ide { 0x1FFF_FFFF } else { 0x7FF }, dlc, &data) };
            if accept(afm, acr, amr, &f) {
                exp.push(f.clone());
                accepted_any += 1;
            } else {
                rejected_any += 1;
            }
            n.xmit(0, &f);
            n.run_until(400 * BIT, |n| !n.drv[0].tx_busy);
        }
        n.run(10 * BIT);
        assert_eq!(n.drv[1].rx[before..], exp[..], "round {round} afm {afm} acr {acr:x?} amr {amr:x?}");
    }
    assert!(accepted_any >= 5 && rejected_any >= 5, "{accepted_any} {rejected_any}");
}

#[test]
fn sja_filter_single() {
    run_filter(true, 1);
}

#[test]
fn sja_filter_dual() {
    run_filter(false, 2);
}

#[test]
fn sja_filter_self_reception_is_filtered() {
    // SRR frames pass the own acceptance filter before entering the own FIFO
    let mut n = Net::new(1);
    n.open(0, CtrlMode { loopback: true, presume_ack: true, ..Default::default() });
    n.set_reset_mode(0);
    n.wr(0, REG_ACCC0, 0x24);
    n.wr(0, REG_ACCC0 + 1, 0x60);
    n.wr(0, REG_ACCM0, 0x00);
    n.wr(0, REG_ACCM0 + 1, 0x0F);
    n.wr(0, REG_ACCM0 + 2, 0xFF);
    n.wr(0, REG_ACCM0 + 3, 0xFF);
    // single filter mode (the Linux driver never sets AFM), self test
    n.wr(0, REG_MOD, MOD_AFM | MOD_STM);
    n.wr(0, REG_IER, 0x7F);
    n.run(13 * BIT);
    for id in [0x123u32, 0x124] {
        n.xmit(0, &Frame::std(id, &[id as u8]));
        n.run_until(400 * BIT, |n| !n.drv[0].tx_busy);
    }
    n.run(5 * BIT);
    assert_eq!(n.drv[0].rx, vec![Frame::std(0x123, &[0x23])]);
    assert_eq!(n.drv[0].tx_packets, 2);
}
