//! The register block against its register table (`sja1000::regs`): the
//! value of every address after a hardware reset, the bits a write changes
//! in each mode for every plain register, and addresses without a register.
mod sja1000_util;
use canstar_controller::sja1000::regs::{self, REGS};
use canstar_controller::sja1000::*;
use sja1000_util::*;

/// Every plain register address readable in a mode, with its write mask.
fn plain(reset_mode: bool) -> Vec<(u8, u8, &'static str)> {
    let mut v = vec![];
    for r in REGS.iter().filter(|r| r.plain) {
        if let Some(a) = r.access(reset_mode).filter(|a| a.read) {
            for k in 0..r.len {
                v.push((r.addr + k, a.wmask, r.name));
            }
        }
    }
    v
}

#[test]
fn every_address_reads_its_reset_value_after_a_hardware_reset() {
    let mut n = Net::with_reset_timing(1, 0x41, 0x2F);
    let mut checked = 0;
    for a in 0..128u8 {
        let got = n.rd(0, a);
        let want = match regs::find(a, true, false) {
            // BTR0/BTR1: the power-up values of this build
            Some(r) if r.name == "BTR0" => Some(0x41),
            Some(r) if r.name == "BTR1" => Some(0x2F),
            Some(r) => r.reset,
            // no register, or write only
            None => Some(0x00),
        };
        if let Some(w) = want {
            assert_eq!(got, w, "address {a:#04x} ({:?})", regs::find(a, true, false).map(|r| r.name));
            checked += 1;
        }
    }
    // (ACR, the FIFO RAM and the transmit buffer are not reset)
    assert_eq!(checked, 128 - 4 - 64 - 13);
    // the mirror: address bit 7 is ignored
    assert_eq!(n.rd(0, 0x80 | REG_EWL), regs::EWL.reset.unwrap());
    assert_eq!(n.rd(0, 0x80 | REG_MOD), MOD_RM);
}

#[test]
fn plain_registers_take_exactly_their_write_mask_in_each_mode() {
    for reset_mode in [true, false] {
        let mut n = Net::new(1);
        if !reset_mode {
            n.wr(0, REG_MOD, 0);
            assert_eq!(n.rd(0, REG_MOD) & MOD_RM, 0, "operating mode");
        }
        let regs = plain(reset_mode);
        assert!(regs.len() > 60, "{} plain registers", regs.len());
        for &(a, wmask, name) in &regs {
            let mut cur = n.rd(0, a);
            for pattern in [0xFF, 0x00, 0xA5, 0x5A] {
                n.wr(0, a, pattern);
                let want = (cur & !wmask) | (pattern & wmask);
                assert_eq!(n.rd(0, a), want, "{name} at {a:#04x}, reset mode {reset_mode}, wrote {pattern:#04x}");
                cur = want;
            }
        }
    }
}

#[test]
fn writes_to_addresses_without_a_register_change_nothing() {
    for reset_mode in [true, false] {
        let mut n = Net::new(1);
        if !reset_mode {
            n.wr(0, REG_MOD, 0);
        }
        let regs = plain(reset_mode);
        let before: Vec<u8> = regs.iter().map(|&(a, _, _)| n.rd(0, a)).collect();
        let empty: Vec<u8> = (0..128u8).filter(|&a| regs::find(a, reset_mode, true).is_none()).collect();
        assert!(empty.contains(&0x05) && empty.contains(&0x09) && empty.contains(&0x7F));
        for &a in &empty {
            n.wr(0, a, 0xFF);
            n.wr(0, a | 0x80, 0x5A);
        }
        let after: Vec<u8> = regs.iter().map(|&(a, _, _)| n.rd(0, a)).collect();
        assert_eq!(before, after, "reset mode {reset_mode}");
        // and write-only or absent registers read 0
        for a in (0..128u8).filter(|&a| regs::find(a, reset_mode, false).is_none()) {
            assert_eq!(n.rd(0, a), 0, "{a:#04x} reads 0 (reset mode {reset_mode})");
        }
    }
}
