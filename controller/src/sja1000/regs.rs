//! The register table of the SJA1000 (PeliCAN mode) block: one description
//! per register (address, access in operating and in reset mode, value after
//! a hardware reset, bit names as in Linux `sja1000.h`).
//!
//! This table is the single source of the register map: the `REG_*`
//! addresses below are taken from it, the RTL ([`super::top`]) compares bus
//! addresses against `Constant` fields initialised from it (`#[hdl_gen]`
//! cannot read Rust constants), and the tests check the block against it
//! (reset values, which bits a write changes in each mode).
//!
//! Addresses are 7 bits (bit 7 of the bus address is ignored). At
//! 0x10..0x1C the two modes differ: reset mode has the acceptance code and
//! mask registers (and 0x18..0x1C read 0), operating mode the receive
//! window (read) and the transmit buffer (write). Addresses without an
//! entry read 0x00 and ignore writes.

/// How a register behaves in one mode.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Access {
    /// A read returns the register (otherwise 0x00).
    pub read: bool,
    /// The bits a write changes (0: no write).
    pub wmask: u8,
}

/// Read only.
pub const RO: Access = Access { read: true, wmask: 0x00 };
/// Read and write.
pub const RW: Access = Access { read: true, wmask: 0xFF };
/// Write only (reads 0x00).
pub const WO: Access = Access { read: false, wmask: 0xFF };

/// One register (or a window of `len` consecutive byte registers).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Reg {
    pub name: &'static str,
    pub addr: u8,
    pub len: u8,
    /// Access in operating mode (`None`: not at this address in this mode).
    pub op: Option<Access>,
    /// Access in reset mode.
    pub rm: Option<Access>,
    /// Value after a hardware reset (`None`: not reset, or not a stored
    /// value). BTR0/BTR1 reset to 0 unless the block is built with other
    /// power-up values ([`super::Sja1000::with_reset_timing`]).
    pub reset: Option<u8>,
    /// Bit names, bit 7 first ("" for an unused bit); for windows, empty.
    pub bits: [&'static str; 8],
    /// Reads and writes have no side effect and the value is simply stored
    /// (a table-driven test writes and reads these back).
    pub plain: bool,
}

const NONE: [&str; 8] = [""; 8];

const fn reg(name: &'static str, addr: u8, op: Option<Access>, rm: Option<Access>, reset: Option<u8>, bits: [&'static str; 8], plain: bool) -> Reg {
    Reg { name, addr, len: 1, op, rm, reset, bits, plain }
}

const fn window(name: &'static str, addr: u8, len: u8, op: Option<Access>, rm: Option<Access>, reset: Option<u8>, plain: bool) -> Reg {
    Reg { name, addr, len, op, rm, reset, bits: NONE, plain }
}

const fn wm(wmask: u8) -> Access {
    Access { read: true, wmask }
}

/// Mode: RM (bit 0) enters/leaves reset mode; LOM, STM, AFM are writable
/// in reset mode, SM (sleep) in operating mode.
pub const MOD: Reg = reg("MOD", 0x00, Some(wm(0x11)), Some(wm(0x0F)), Some(0x01), ["", "", "", "SM", "AFM", "STM", "LOM", "RM"], false);
/// Command (write only); TR, AT, SRR act in operating mode only.
pub const CMR: Reg = reg("CMR", 0x01, Some(WO), Some(Access { read: false, wmask: 0x0C }), Some(0x00), ["", "", "", "SRR", "CDO", "RRB", "AT", "TR"], false);
/// Status.
pub const SR: Reg = reg("SR", 0x02, Some(RO), Some(RO), Some(0x3C), ["BS", "ES", "TS", "RS", "TCS", "TBS", "DOS", "RBS"], false);
/// Interrupt (a read clears all but RI).
pub const IR: Reg = reg("IR", 0x03, Some(RO), Some(RO), Some(0x00), ["BEI", "ALI", "EPI", "WUI", "DOI", "EI", "TI", "RI"], false);
/// Interrupt enable.
pub const IER: Reg = reg("IER", 0x04, Some(RW), Some(RW), Some(0x00), ["BEIE", "ALIE", "EPIE", "WUIE", "DOIE", "EIE", "TIE", "RIE"], true);
/// Bus timing 0.
pub const BTR0: Reg = reg("BTR0", 0x06, Some(RO), Some(RW), Some(0x00), ["SJW1", "SJW0", "BRP5", "BRP4", "BRP3", "BRP2", "BRP1", "BRP0"], true);
/// Bus timing 1.
pub const BTR1: Reg = reg("BTR1", 0x07, Some(RO), Some(RW), Some(0x00), ["SAM", "TSEG2.2", "TSEG2.1", "TSEG2.0", "TSEG1.3", "TSEG1.2", "TSEG1.1", "TSEG1.0"], true);
/// Output control (stored only).
pub const OCR: Reg = reg("OCR", 0x08, Some(RO), Some(RW), Some(0x00), ["OCTP1", "OCTN1", "OCPOL1", "OCTP0", "OCTN0", "OCPOL0", "OCMODE1", "OCMODE0"], true);
/// Arbitration lost capture (a read re-arms it).
pub const ALC: Reg = reg("ALC", 0x0B, Some(RO), Some(RO), Some(0x00), ["", "", "", "BITNO4", "BITNO3", "BITNO2", "BITNO1", "BITNO0"], false);
/// Error code capture (a read re-arms it).
pub const ECC: Reg = reg("ECC", 0x0C, Some(RO), Some(RO), Some(0x00), ["ERRC1", "ERRC0", "DIR", "SEG4", "SEG3", "SEG2", "SEG1", "SEG0"], false);
/// Error warning limit.
pub const EWL: Reg = reg("EWL", 0x0D, Some(RO), Some(RW), Some(96), NONE, true);
/// Receive error counter (the core's REC).
pub const RXERR: Reg = reg("RXERR", 0x0E, Some(RO), Some(RW), Some(0x00), NONE, false);
/// Transmit error counter (the core's TEC).
pub const TXERR: Reg = reg("TXERR", 0x0F, Some(RO), Some(RW), Some(0x00), NONE, false);
/// Acceptance code 0..3 (reset mode; not reset).
pub const ACR: Reg = window("ACR", 0x10, 4, None, Some(RW), None, true);
/// Acceptance mask 0..3 (reset mode).
pub const AMR: Reg = window("AMR", 0x14, 4, None, Some(RW), Some(0xFF), true);
/// Receive window: FIFO RAM from RBSA (operating mode, read).
pub const RXBUF: Reg = window("RXBUF", 0x10, 13, Some(RO), None, None, false);
/// Transmit buffer (operating mode, write; ignored while TBS = 0).
pub const TXBUF: Reg = window("TXBUF", 0x10, 13, Some(WO), None, None, false);
/// Receive message counter.
pub const RMC: Reg = reg("RMC", 0x1D, Some(RO), Some(RO), Some(0x00), NONE, false);
/// Receive buffer start address (6 bits; a write empties the FIFO).
pub const RBSA: Reg = reg("RBSA", 0x1E, Some(RO), Some(wm(0x3F)), Some(0x00), NONE, false);
/// Clock divider: bits 3..0 writable always, bits 7..5 in reset mode only,
/// bit 4 reads 0.
pub const CDR: Reg = reg("CDR", 0x1F, Some(wm(0x0F)), Some(wm(0xEF)), Some(0x00), ["PELICAN", "CBP", "RXINTEN", "", "CLKOFF", "CD2", "CD1", "CD0"], true);
/// The FIFO RAM (64 bytes; zero at power-up, not reset).
pub const RXFIFO: Reg = window("RXFIFO", 0x20, 64, Some(RO), Some(RW), None, true);
/// The transmit buffer, readable always (not reset).
pub const TXB: Reg = window("TXB", 0x60, 13, Some(RO), Some(RW), None, true);

/// Every register, by address.
pub const REGS: [Reg; 22] = [
    MOD, CMR, SR, IR, IER, BTR0, BTR1, OCR, ALC, ECC, EWL, RXERR, TXERR, ACR, AMR, RXBUF, TXBUF, RMC, RBSA, CDR, RXFIFO, TXB,
];

impl Reg {
    /// The access of this register in a mode (`None`: not there).
    pub fn access(&self, reset_mode: bool) -> Option<Access> {
        if reset_mode {
            self.rm
        } else {
            self.op
        }
    }
    /// `addr` lies in this register (window).
    pub fn contains(&self, addr: u8) -> bool {
        (self.addr..self.addr + self.len).contains(&(addr & 0x7F))
    }
    /// Last address of the register (window).
    pub const fn last(&self) -> u8 {
        self.addr + self.len - 1
    }
}

/// The register a read (`write` false) or a write at `addr` reaches in a
/// mode, if any.
pub fn find(addr: u8, reset_mode: bool, write: bool) -> Option<&'static Reg> {
    REGS.iter().find(|r| {
        r.contains(addr)
            && r.access(reset_mode).is_some_and(|a| if write { a.wmask != 0 } else { a.read })
    })
}

const fn str_eq(a: &str, b: &str) -> bool {
    let (a, b) = (a.as_bytes(), b.as_bytes());
    if a.len() != b.len() {
        return false;
    }
    let mut i = 0;
    while i < a.len() {
        if a[i] != b[i] {
            return false;
        }
        i += 1;
    }
    true
}

/// The mask of the bit called `name` in `reg` (a compile-time error if
/// there is none).
pub const fn mask(reg: Reg, name: &str) -> u8 {
    let mut i = 0;
    while i < 8 {
        if str_eq(reg.bits[i], name) {
            return 0x80 >> i;
        }
        i += 1;
    }
    panic!("no such bit")
}

/// The position (0..7) of a one-bit mask.
pub const fn pos(mask: u8) -> usize {
    mask.trailing_zeros() as usize
}

// ---- addresses (from the table) ----
pub const REG_MOD: u8 = MOD.addr;
pub const REG_CMR: u8 = CMR.addr;
pub const REG_SR: u8 = SR.addr;
pub const REG_IR: u8 = IR.addr;
pub const REG_IER: u8 = IER.addr;
pub const REG_BTR0: u8 = BTR0.addr;
pub const REG_BTR1: u8 = BTR1.addr;
pub const REG_OCR: u8 = OCR.addr;
pub const REG_ALC: u8 = ALC.addr;
pub const REG_ECC: u8 = ECC.addr;
pub const REG_EWL: u8 = EWL.addr;
pub const REG_RXERR: u8 = RXERR.addr;
pub const REG_TXERR: u8 = TXERR.addr;
pub const REG_ACCC0: u8 = ACR.addr;
pub const REG_ACCM0: u8 = AMR.addr;
/// Frame information byte of the receive window / transmit buffer.
pub const REG_FI: u8 = RXBUF.addr;
pub const REG_ID1: u8 = RXBUF.addr + 1;
pub const REG_RMC: u8 = RMC.addr;
pub const REG_RBSA: u8 = RBSA.addr;
pub const REG_CDR: u8 = CDR.addr;
pub const REG_RXFIFO: u8 = RXFIFO.addr;
/// The transmit buffer as readable at 0x60 (written at 0x10 in operating mode).
pub const REG_TXBUF: u8 = TXB.addr;

// ---- bits (from the table's bit names) ----
pub const MOD_RM: u8 = mask(MOD, "RM");
pub const MOD_LOM: u8 = mask(MOD, "LOM");
pub const MOD_STM: u8 = mask(MOD, "STM");
pub const MOD_AFM: u8 = mask(MOD, "AFM");
pub const MOD_SM: u8 = mask(MOD, "SM");

pub const CMD_TR: u8 = mask(CMR, "TR");
pub const CMD_AT: u8 = mask(CMR, "AT");
pub const CMD_RRB: u8 = mask(CMR, "RRB");
pub const CMD_CDO: u8 = mask(CMR, "CDO");
pub const CMD_SRR: u8 = mask(CMR, "SRR");

pub const SR_RBS: u8 = mask(SR, "RBS");
pub const SR_DOS: u8 = mask(SR, "DOS");
pub const SR_TBS: u8 = mask(SR, "TBS");
pub const SR_TCS: u8 = mask(SR, "TCS");
pub const SR_RS: u8 = mask(SR, "RS");
pub const SR_TS: u8 = mask(SR, "TS");
pub const SR_ES: u8 = mask(SR, "ES");
pub const SR_BS: u8 = mask(SR, "BS");

pub const IRQ_RI: u8 = mask(IR, "RI");
pub const IRQ_TI: u8 = mask(IR, "TI");
pub const IRQ_EI: u8 = mask(IR, "EI");
pub const IRQ_DOI: u8 = mask(IR, "DOI");
pub const IRQ_WUI: u8 = mask(IR, "WUI");
pub const IRQ_EPI: u8 = mask(IR, "EPI");
pub const IRQ_ALI: u8 = mask(IR, "ALI");
pub const IRQ_BEI: u8 = mask(IR, "BEI");

/// ECC: segment code, direction (1 = receiving), error code.
pub const ECC_SEG: u8 = mask(ECC, "SEG4") | mask(ECC, "SEG3") | mask(ECC, "SEG2") | mask(ECC, "SEG1") | mask(ECC, "SEG0");
pub const ECC_DIR: u8 = mask(ECC, "DIR");
pub const ECC_MASK: u8 = mask(ECC, "ERRC1") | mask(ECC, "ERRC0");
/// Error codes (the ECC_MASK field).
pub const ECC_BIT: u8 = 0x00;
pub const ECC_FORM: u8 = mask(ECC, "ERRC0");
pub const ECC_STUFF: u8 = mask(ECC, "ERRC1");
pub const ECC_OTHER: u8 = ECC_MASK;

/// Frame information byte (first byte of a message in the receive window
/// and the transmit buffer): FF (extended frame), RTR, bits 3..0 DLC.
pub const FI_FF: u8 = 0x80;
pub const FI_RTR: u8 = 0x40;
pub const CDR_PELICAN: u8 = mask(CDR, "PELICAN");

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_matches_the_pelican_map() {
        // the documented masks (Linux sja1000.h) follow from the bit names
        assert_eq!((MOD_RM, MOD_LOM, MOD_STM, MOD_AFM, MOD_SM), (0x01, 0x02, 0x04, 0x08, 0x10));
        assert_eq!((CMD_TR, CMD_AT, CMD_RRB, CMD_CDO, CMD_SRR), (0x01, 0x02, 0x04, 0x08, 0x10));
        assert_eq!([SR_RBS, SR_DOS, SR_TBS, SR_TCS, SR_RS, SR_TS, SR_ES, SR_BS], [1, 2, 4, 8, 16, 32, 64, 128]);
        assert_eq!([IRQ_RI, IRQ_TI, IRQ_EI, IRQ_DOI, IRQ_WUI, IRQ_EPI, IRQ_ALI, IRQ_BEI], [1, 2, 4, 8, 16, 32, 64, 128]);
        assert_eq!((ECC_SEG, ECC_DIR, ECC_MASK, ECC_FORM, ECC_STUFF), (0x1F, 0x20, 0xC0, 0x40, 0x80));
        assert_eq!(CDR_PELICAN, 0x80);
        assert_eq!(
            [REG_MOD, REG_CMR, REG_SR, REG_IR, REG_IER, REG_BTR0, REG_BTR1, REG_OCR, REG_ALC, REG_ECC, REG_EWL, REG_RXERR, REG_TXERR],
            [0, 1, 2, 3, 4, 6, 7, 8, 11, 12, 13, 14, 15]
        );
        assert_eq!([REG_RMC, REG_RBSA, REG_CDR, REG_RXFIFO, REG_TXBUF], [0x1D, 0x1E, 0x1F, 0x20, 0x60]);
    }

    #[test]
    fn each_address_has_at_most_one_register_per_mode_and_direction() {
        for a in 0..128u8 {
            for rm in [false, true] {
                for w in [false, true] {
                    let n = REGS
                        .iter()
                        .filter(|r| r.contains(a) && r.access(rm).is_some_and(|x| if w { x.wmask != 0 } else { x.read }))
                        .count();
                    assert!(n <= 1, "address {a:#04x} reset mode {rm} write {w}: {n} registers");
                }
            }
        }
        // the two modes differ only at 0x10..0x1C
        assert_eq!(find(0x10, true, false).unwrap().name, "ACR");
        assert_eq!(find(0x14, true, true).unwrap().name, "AMR");
        assert_eq!(find(0x10, false, false).unwrap().name, "RXBUF");
        assert_eq!(find(0x10, false, true).unwrap().name, "TXBUF");
        assert!(find(0x18, true, false).is_none());
        assert!(find(0x05, false, false).is_none() && find(0x09, true, true).is_none() && find(0x6D, true, false).is_none());
        assert_eq!(find(0x80 | REG_SR, false, false).unwrap().name, "SR", "address bit 7 ignored");
    }
}
