//! The stufferr program of conformance-tests.md §12 on the bit-level
//! harness: N1 transmits, N2 receives, the named stuff bit is forced at both
//! nodes. N1: +8 (EXC2 inside arbitration: +0), N2: +1; both flags start
//! together, so no dominant-bit-after-flag penalty.
mod common;
use canstar_controller::frame::{bus_bits, BuildOptions, BusBit, Frame};
use canstar_controller::fsm::*;
use common::*;

#[track_caller]
fn find(ide: bool, want: impl Fn(&[BusBit]) -> bool) -> Frame {
    for k in 0u64..400_000 {
        let id = if ide { (k.wrapping_mul(2_654_435_761) & 0x1FFF_FFFF) as u32 } else { (k & 0x7FF) as u32 };
        let dlc = 8 - ((k >> 11) % 9) as u8;
        let x = k.wrapping_mul(0x9E37_79B9_7F4A_7C15);
        let pats = [0x00u8, 0xFF, 0x0F, 0xF0, 0x83, 0x7C];
        let data: Vec<u8> = (0..8).map(|i| pats[((x >> (6 * i)) % 6) as usize]).collect();
        for f in [Frame::data(ide, id, dlc, &data), Frame::remote(ide, id, dlc)] {
            if want(&bus_bits(&f, BuildOptions::default(), true)) {
                return f;
            }
        }
    }
    panic!("no frame found");
}

fn stuff_level(bits: &[BusBit], f: Field, pos: u8) -> Option<bool> {
    bits.iter().find(|b| b.field == f && b.pos == pos && b.stuff).map(|b| b.level)
}

#[test]
fn stufferr_program() {
    // (name, extended, field, pos, stuff level, expected N1 TEC delta)
    // stufferr_5 and _8 (a dominant stuff bit after DLC 2 / DLC 4) need five
    // recessive bits ending there, which includes the dominant r0: no frame the
    // RTL sends has them (a scripted transmitter with a recessive r0 would).
    let steps: [(&str, bool, Field, u8, bool, u64); 14] = [
        ("stufferr_1", false, Field::Ident, 8, false, 8),
        ("stufferr_2", false, Field::Ident, 4, true, 0),
        ("stufferr_3", true, Field::Rtr, 1, true, 8),
        ("stufferr_4", false, Field::Rtr, 1, false, 8),
        ("stufferr_6", false, Field::Dlc, 2, true, 8),
        ("stufferr_7", false, Field::Dlc, 4, true, 8),
        ("stufferr_9", false, Field::Data, 8, false, 8),
        ("stufferr_10", false, Field::Data, 12, true, 8),
        ("stufferr_11", false, Field::Data, 64, true, 8),
        ("stufferr_12", true, Field::Data, 8, false, 8),
        ("stufferr_13", false, Field::Crc, 8, false, 8),
        ("stufferr_14", false, Field::Crc, 1, true, 8),
        ("stufferr_15", false, Field::Crc, 15, true, 8),
        ("stufferr_16", false, Field::Crc, 15, false, 8),
    ];
    let mut b = Bus::integrated(2);
    for (name, ide, field, pos, level, dt) in steps {
        let f = find(ide, |x| stuff_level(x, field, pos) == Some(level));
        let (t0, r0) = (b.tec(0), b.rec(1));
        b.request(0, &f);
        b.run_to_stuff(0, field, pos, 600);
        let o = if level { Ovr::StuckD } else { Ovr::StuckR };
        b.ovr = vec![o, o];
        b.step();
        b.ovr = vec![Ovr::None, Ovr::None];
        let n1 = b.last(0).clone();
        let n2 = b.last(1).clone();
        if level {
            assert!(n1.has(EV_STUFF_ERR), "{name}: {n1:?}");
            assert_eq!(n1.has(EV_EXC2), dt == 0, "{name}");
        } else {
            assert!(n1.has(EV_BIT_ERR), "{name}: {n1:?}");
        }
        assert!(n2.has(EV_STUFF_ERR) && n2.stuff, "{name}: {n2:?}");
        b.run_until(30, |b| b.field(0) == Field::ErrDel && b.field(1) == Field::ErrDel);
        assert_eq!(b.tec(0), t0 + dt, "{name}");
        assert_eq!(b.rec(1), r0 + 1, "{name}");
        // the retry succeeds
        b.run_until(600, |b| b.nodes[0].tx_done.val());
        b.withdraw(0);
        b.run_idle(60);
        assert_eq!(b.rx[1].last(), Some(&f), "{name}");
    }
}
