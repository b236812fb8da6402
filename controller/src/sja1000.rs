//! [`Sja1000`]: an NXP SJA1000 (PeliCAN mode) compatible register block on a
//! Wishbone B4 classic slave, wrapping [`CanCore`], with the 64-byte receive
//! FIFO (one block RAM), the acceptance filters and the interrupt logic.
//!
//! The goal is that existing SJA1000 software (the Linux `sja1000` driver
//! family, Zephyr's `can_sja1000`) drives the core unchanged. The register
//! map is the PeliCAN map of the SJA1000 data sheet; bit names below are the
//! Linux `sja1000.h` names.
//!
//! # Ports
//!
//! - `clock`: the single clock, shared with the CAN core (the SJA1000's
//!   XTAL1: one time quantum is 2·(BRP+1) clocks).
//! - `rst`: synchronous hardware reset (the SJA1000's RST pin), active high.
//!   Assert it for at least one clock after power-up.
//! - Wishbone B4 classic slave, 8-bit data, 8-bit address: `wb_cyc`,
//!   `wb_stb`, `wb_we`, `wb_adr`, `wb_dat_w` in; `wb_dat_r`, `wb_ack` out.
//!   Every access takes two clocks: `wb_ack` is high on the clock after the
//!   one on which `wb_cyc & wb_stb` was first seen, with `wb_dat_r` valid on
//!   that clock. A write, and the side effects of a read (IR, ALC and ECC
//!   reads), happen once, on the first clock. Address bit 7 is ignored
//!   (128..255 mirror 0..127, as on the SJA1000's multiplexed bus).
//! - `rx` (bus level, 1 = recessive, asynchronous: synchronised by the
//!   core) and `tx` (registered, 1 = recessive).
//! - `int_n`: interrupt, active low like the SJA1000's INT pin (low while
//!   any bit of IR is set). Registered state only, no combinational path
//!   from the bus.
//!
//! # Register map (address: operating mode read / write; reset mode)
//!
//! | addr | name | notes |
//! |---|---|---|
//! | 0x00 | MOD | RM (bit 0), LOM, STM, AFM writable in reset mode only; SM (bit 4) in operating mode only |
//! | 0x01 | CMR | write only, reads 0x00: TR, AT, RRB, CDO, SRR |
//! | 0x02 | SR | BS, ES, TS, RS, TCS, TBS, DOS, RBS |
//! | 0x03 | IR | BEI ALI EPI WUI DOI EI TI RI; a read clears all but RI |
//! | 0x04 | IER | same bit layout, always writable |
//! | 0x06/0x07 | BTR0/BTR1 | writable in reset mode |
//! | 0x08 | OCR | stored and read back, writable in reset mode |
//! | 0x0B | ALC | arbitration lost capture (bits 4..0) |
//! | 0x0C | ECC | error code capture |
//! | 0x0D | EWL | error warning limit (96 after reset), writable in reset mode |
//! | 0x0E/0x0F | RXERR/TXERR | the core's error counters; writable in reset mode |
//! | 0x10..0x1C | operating mode: read = RX window (FIFO RAM from RBSA), write = TX buffer |
//! | 0x10..0x17 | reset mode: ACR0..3, AMR0..3 (0x18..0x1C read 0) |
//! | 0x1D | RMC | RX message counter |
//! | 0x1E | RBSA | RX buffer start address (writable in reset mode) |
//! | 0x1F | CDR | clock divider; bits 7..5 writable in reset mode only |
//! | 0x20..0x5F | RX FIFO RAM, readable always, writable in reset mode |
//! | 0x60..0x6C | TX buffer, readable always, writable in reset mode |
//! | others | read 0x00, writes ignored (0x05, 0x09 test, 0x0A, 0x6D..0x7F) |
//!
//! # Behaviour and differences from a real SJA1000
//!
//! - **Reset mode** holds the core in reset (the core latches the bit timing
//!   then). Entering it cancels a pending transmission (TBS = 1, no TI),
//!   empties the FIFO (RMC = 0; RBSA is kept, the next message is stored at
//!   RBSA) and leaves sleep. Writing RBSA empties the FIFO too.
//! - **Error counters** are the core's TEC and REC. Entering reset mode
//!   keeps them: while in reset mode the core is held in reset with its
//!   counters loaded (`cnt_load`) from their own values or from a host
//!   write to TXERR/RXERR, so the core continues from them when reset mode
//!   is left; only the hardware reset clears them. As on the SJA1000, the
//!   error state follows from the written values (error-passive from 128),
//!   but ES, BS and the EI/EPI interrupts they cause change only when reset
//!   mode is left: SR bits 7 and 6 are frozen in reset mode. Writing 255 to
//!   TXERR is a CPU-driven bus-off (TXERR reads 255 until then): leaving
//!   reset mode performs the bus-off event (RM set again, TXERR 127, RXERR 0,
//!   BS, ES, EI), and clearing RM once more starts the recovery.
//! - **Bus-off** sets RM; the core is then *not* reset but stays in its
//!   bus-off state (`host_recovery` = 1). While bus-off, TXERR reads
//!   127 − (completed recovery runs), counting down like the SJA1000's, and
//!   RXERR reads 0 (writes to it have no effect). Clearing RM starts the
//!   recovery of 128 × 11 recessive bits (the core's `recover` strobe); at
//!   its end BS and ES clear and EI is raised. Writing TXERR 0..254 while
//!   bus-off clears BS at once and loads the core with the value (REC 0),
//!   so it only waits for 11 recessive bits after RM is cleared; writing 255
//!   then restarts the bus-off (a new bus-off event when RM is cleared).
//!   Bit timing changes made while bus-off take effect at the next reset
//!   mode entry that is not a bus-off (or after such a TXERR write).
//!   Entering reset mode during the recovery does not freeze TXERR: the
//!   recovery keeps counting (the SJA1000 freezes it).
//! - **Bit timing**: BTR0/BTR1 are mapped onto the core's fields. Every BRP
//!   0..63 is exact: TQ = 2·(BRP+1) clocks (the core's prescaler field is
//!   2·BRP+1, 7 bits). With t1 = TSEG1+1 (1..16 TQ) and t2 = TSEG2+1
//!   (1..8 TQ) the bit is 1 + t1 + t2 TQ; the core has PH2 = max(PH1, 2),
//!   PROP 1..16, PH1 1..8. When t1 > t2 ≥ 2 the mapping is exact: PROP =
//!   t1 − t2, PH1 = PH2 = t2 (sample point after 1 + t1 TQ, as on the
//!   SJA1000). The other settings keep the bit time and move the sample
//!   point: t2 = 1 gives PROP = t1 − 2, PH1 = 1, PH2 = 2 (sample point one TQ
//!   earlier); t1 ≤ t2 gives PH1 = PH2 = ⌊(t1 + t2 − 1)/2⌋ and PROP =
//!   t1 + t2 − 2·PH1 (1 or 2; sample point later). SJW is limited to PH1
//!   (so to t2 in the exact case). Bit times below 8 TQ are rejected by the
//!   core (it stays inert, TX recessive, RS = TS = 1). SAM selects triple
//!   sampling.
//! - **TS/RS** are both 1 while the core waits for bus idle (reset, the
//!   11-bit integration, bus-off), as the SJA1000's 0x3C status after reset;
//!   otherwise TS = transmitting, RS = receiving a frame (SOF to the end of
//!   error/overload frames).
//! - **Commands**: TR and SRR are taken in operating mode when TBS = 1 and
//!   the node is not sleeping (else ignored); with AT in the same write the
//!   transmission is single shot. AT alone while a transmission is pending
//!   aborts it: if it has not started TBS = 1 at once, else at the end of
//!   the frame; TCS tells whether it was sent. TI is raised whenever TBS
//!   goes back to 1 (success, single-shot failure, abort). Writes to the TX
//!   buffer while TBS = 0 are ignored (the SJA1000 locks it).
//!   In listen-only mode a request stays pending (the core never transmits).
//! - **Self-reception** (SRR): the core does not deliver its own frames, so
//!   after a successful SRR transmission the block copies the TX buffer
//!   into the RX FIFO itself (through the acceptance filter, with data
//!   overrun when full); TBS is released (and TI raised) when that copy is
//!   done, a few clocks after the frame. Frames sent with TR are not
//!   received back. Self-test mode (STM) makes the core accept a missing ACK.
//! - **RX FIFO**: 64 bytes of block RAM; a message takes 3 + n (standard) or
//!   5 + n (extended) bytes, n = 0 for remote frames, else min(DLC, 8); the
//!   raw DLC is stored. A message that does not fit is dropped whole and
//!   sets DOS (DOI on its rising edge); RMC is not incremented for it. The
//!   RX window (0x10..0x1C) is RAM[(RBSA + k) mod 64] as on the SJA1000.
//!   Unused bits of received frames read 0 (FI bits 5..4, SFF ID2 bits 3..0,
//!   EFF ID4 bits 1..0); ID2 bit 4 (SFF) / ID4 bit 2 (EFF) show RTR.
//! - **Acceptance filter**: single and dual filter as in the data sheet.
//!   Data bytes that the frame does not carry (remote frames, DLC < 2) match
//!   any code; the unused code bits (single SFF ACR1.3..0, single EFF
//!   ACR3.1..0) are don't care.
//! - **ALC/ECC** capture on every arbitration loss / bus error while
//!   re-armed; a read re-arms the capture. ALC = core position − 1 (0..31,
//!   SJA1000 coding: 11 = SRR/standard RTR, 12 = IDE, 31 = extended RTR).
//!   ECC: error code (bit, form, stuff, other = CRC or ACK error), DIR
//!   (1 = receiving) and the SJA1000 segment code derived from the core's
//!   FIELD/POSITION. The overload delimiter maps to 0x17 (delimiter);
//!   bit errors in Suspend/Intermission map to 0x12.
//! - **Interrupts**: every IR bit is set only if its IER bit is set at the
//!   time of the event. RI = RIE & RBS (level). EI on any change of ES or BS.
//!   EPI when the node becomes error-passive and when it returns from
//!   error-passive to error-active (not on passive -> bus-off). BEI on every
//!   bus error, ALI on every arbitration loss, DOI on the rising edge of DOS.
//! - **Sleep** (SM): accepted in operating mode when no interrupt is pending,
//!   the bus is idle and no transmission is pending; otherwise the write is
//!   ignored (SM reads 0). There is no clock to stop in an FPGA: while
//!   sleeping the core keeps running; a dominant bit on the bus, a write of
//!   SM = 0 or entering reset mode wakes the node and raises WUI. Unlike
//!   the SJA1000 the frame that woke the node is received normally.
//! - **OCR** is stored and read back only: the FPGA has one TX pin, output
//!   mode/polarity are the board's business. **CDR**: all bits are stored and
//!   read back (reset value 0x00); the block is always PeliCAN (CDR.7 = 0 does
//!   not select BasicCAN), there is no CLKOUT, no RX comparator bypass and no
//!   TX1 interrupt output, so CBP, RXINTEN, clock off and CD have no effect.
//! - The test register (0x09) is not implemented (reads 0).

use crate::core::CanCore;
use rust_hdl::prelude::*;

pub const REG_MOD: u8 = 0x00;
pub const REG_CMR: u8 = 0x01;
pub const REG_SR: u8 = 0x02;
pub const REG_IR: u8 = 0x03;
pub const REG_IER: u8 = 0x04;
pub const REG_BTR0: u8 = 0x06;
pub const REG_BTR1: u8 = 0x07;
pub const REG_OCR: u8 = 0x08;
pub const REG_ALC: u8 = 0x0B;
pub const REG_ECC: u8 = 0x0C;
pub const REG_EWL: u8 = 0x0D;
pub const REG_RXERR: u8 = 0x0E;
pub const REG_TXERR: u8 = 0x0F;
pub const REG_ACCC0: u8 = 0x10;
pub const REG_ACCM0: u8 = 0x14;
pub const REG_FI: u8 = 0x10;
pub const REG_ID1: u8 = 0x11;
pub const REG_RMC: u8 = 0x1D;
pub const REG_RBSA: u8 = 0x1E;
pub const REG_CDR: u8 = 0x1F;
pub const REG_RXFIFO: u8 = 0x20;
pub const REG_TXBUF: u8 = 0x60;

pub const MOD_RM: u8 = 0x01;
pub const MOD_LOM: u8 = 0x02;
pub const MOD_STM: u8 = 0x04;
pub const MOD_AFM: u8 = 0x08;
pub const MOD_SM: u8 = 0x10;

pub const CMD_TR: u8 = 0x01;
pub const CMD_AT: u8 = 0x02;
pub const CMD_RRB: u8 = 0x04;
pub const CMD_CDO: u8 = 0x08;
pub const CMD_SRR: u8 = 0x10;

pub const SR_RBS: u8 = 0x01;
pub const SR_DOS: u8 = 0x02;
pub const SR_TBS: u8 = 0x04;
pub const SR_TCS: u8 = 0x08;
pub const SR_RS: u8 = 0x10;
pub const SR_TS: u8 = 0x20;
pub const SR_ES: u8 = 0x40;
pub const SR_BS: u8 = 0x80;

pub const IRQ_RI: u8 = 0x01;
pub const IRQ_TI: u8 = 0x02;
pub const IRQ_EI: u8 = 0x04;
pub const IRQ_DOI: u8 = 0x08;
pub const IRQ_WUI: u8 = 0x10;
pub const IRQ_EPI: u8 = 0x20;
pub const IRQ_ALI: u8 = 0x40;
pub const IRQ_BEI: u8 = 0x80;

pub const ECC_SEG: u8 = 0x1F;
pub const ECC_DIR: u8 = 0x20;
pub const ECC_BIT: u8 = 0x00;
pub const ECC_FORM: u8 = 0x40;
pub const ECC_STUFF: u8 = 0x80;
pub const ECC_OTHER: u8 = 0xC0;
pub const ECC_MASK: u8 = 0xC0;

pub const FI_FF: u8 = 0x80;
pub const FI_RTR: u8 = 0x40;
pub const CDR_PELICAN: u8 = 0x80;

/// The register block (see the module documentation).
/// The BTR0/BTR1 values a hardware reset loads (generation-time constants),
/// output while `en` (the reset) is high. The input matters in Verilog: a
/// combinational block that reads only constants has an empty sensitivity
/// list and would never drive its outputs in an event-driven simulator.
#[derive(LogicBlock)]
pub struct BtrReset {
    pub en: Signal<In, Bit>,
    pub btr0: Signal<Out, Bits<8>>,
    pub btr1: Signal<Out, Bits<8>>,
    v0: Constant<Bits<8>>,
    v1: Constant<Bits<8>>,
}

impl BtrReset {
    pub fn new(btr0: u8, btr1: u8) -> Self {
        Self { en: Default::default(), btr0: Default::default(), btr1: Default::default(), v0: Constant::new((btr0 as u64).into()), v1: Constant::new((btr1 as u64).into()) }
    }
}

impl Default for BtrReset {
    fn default() -> Self {
        Self::new(0, 0)
    }
}

impl Logic for BtrReset {
    #[hdl_gen]
    fn update(&mut self) {
        self.btr0.next = 0.into();
        self.btr1.next = 0.into();
        if self.en.val() {
            self.btr0.next = self.v0.val();
            self.btr1.next = self.v1.val();
        }
    }
}

#[derive(LogicBlock, Default)]
pub struct Sja1000 {
    pub clock: Signal<In, Clock>,
    pub rst: Signal<In, Bit>,
    pub wb_cyc: Signal<In, Bit>,
    pub wb_stb: Signal<In, Bit>,
    pub wb_we: Signal<In, Bit>,
    pub wb_adr: Signal<In, Bits<8>>,
    pub wb_dat_w: Signal<In, Bits<8>>,
    pub wb_dat_r: Signal<Out, Bits<8>>,
    pub wb_ack: Signal<Out, Bit>,
    pub rx: Signal<In, Bit>,
    pub tx: Signal<Out, Bit>,
    pub int_n: Signal<Out, Bit>,

    core: CanCore,
    ram: RAM<Bits<8>, 6>,

    // bus interface
    ack: DFF<Bit>,
    rdat: DFF<Bits<8>>,
    ramsel: DFF<Bit>,
    // mode
    opm: DFF<Bit>, // operating mode (= !RM; 0 at power-up)
    lom: DFF<Bit>,
    stm: DFF<Bit>,
    afm: DFF<Bit>,
    sleep: DFF<Bit>,
    boff: DFF<Bit>, // bus-off hold: RM set by bus-off, core not reset
    core_bs: DFF<Bit>,
    // registers
    ier: DFF<Bits<8>>,
    ir: DFF<Bits<8>>,
    btr0: DFF<Bits<8>>,
    btr1: DFF<Bits<8>>,
    btr_reset: BtrReset,
    ocr: DFF<Bits<8>>,
    ewl: DFF<Bits<8>>,
    cdr: DFF<Bits<8>>,
    alc: DFF<Bits<5>>,
    alc_lock: DFF<Bit>,
    ecc: DFF<Bits<8>>,
    ecc_lock: DFF<Bit>,
    acr0: DFF<Bits<8>>,
    acr1: DFF<Bits<8>>,
    acr2: DFF<Bits<8>>,
    acr3: DFF<Bits<8>>,
    amr0: DFF<Bits<8>>,
    amr1: DFF<Bits<8>>,
    amr2: DFF<Bits<8>>,
    amr3: DFF<Bits<8>>,
    txb0: DFF<Bits<8>>,
    txb1: DFF<Bits<8>>,
    txb2: DFF<Bits<8>>,
    txb3: DFF<Bits<8>>,
    txb4: DFF<Bits<8>>,
    txb5: DFF<Bits<8>>,
    txb6: DFF<Bits<8>>,
    txb7: DFF<Bits<8>>,
    txb8: DFF<Bits<8>>,
    txb9: DFF<Bits<8>>,
    txb10: DFF<Bits<8>>,
    txb11: DFF<Bits<8>>,
    txb12: DFF<Bits<8>>,
    // transmission
    tx_pend: DFF<Bit>,
    tx_single: DFF<Bit>,
    tx_srr: DFF<Bit>,
    tx_abrt: DFF<Bit>,
    tx_lb: DFF<Bit>,
    tcs_n: DFF<Bit>, // !TCS (TCS = 1 after power-up/reset)
    // receive FIFO
    dos: DFF<Bit>,
    rbsa: DFF<Bits<6>>,
    used: DFF<Bits<7>>,
    rmc: DFF<Bits<5>>,
    wr_busy: DFF<Bit>,
    wr_src: DFF<Bit>,
    wr_idx: DFF<Bits<4>>,
    wr_len: DFF<Bits<4>>,
    fetch_q: DFF<Bit>,
    fetch_a: DFF<Bits<6>>,
    cur_fi: DFF<Bits<8>>,
    // status tracking
    es_q: DFF<Bit>,
    bs_q: DFF<Bit>,
    pas_q: DFF<Bit>,
    seen_ext: DFF<Bit>,

    // ---- combinational ----
    l_req: Signal<Local, Bit>,
    l_wr: Signal<Local, Bit>,
    l_rd: Signal<Local, Bit>,
    l_a: Signal<Local, Bits<7>>,
    l_aoff: Signal<Local, Bits<7>>,
    l_alcm1: Signal<Local, Bits<6>>,
    l_d: Signal<Local, Bits<8>>,
    l_rm: Signal<Local, Bit>,
    l_win: Signal<Local, Bit>,
    l_ramrd: Signal<Local, Bit>,
    l_rdv: Signal<Local, Bits<8>>,
    l_sr: Signal<Local, Bits<8>>,
    l_irv: Signal<Local, Bits<8>>,
    l_ev: Signal<Local, Bits<8>>,
    l_tbs: Signal<Local, Bit>,
    l_tcs: Signal<Local, Bit>,
    l_dirrx: Signal<Local, Bit>,
    l_irn: Signal<Local, Bits<8>>,
    l_tecv: Signal<Local, Bits<8>>,
    l_recv: Signal<Local, Bits<8>>,
    l_frz: Signal<Local, Bit>,
    l_cbsr: Signal<Local, Bit>,
    l_cbs: Signal<Local, Bit>,
    l_es: Signal<Local, Bit>,
    l_pas: Signal<Local, Bit>,
    l_cload: Signal<Local, Bit>,
    l_tecin: Signal<Local, Bits<9>>,
    l_recin: Signal<Local, Bits<8>>,
    l_fld: Signal<Local, Bits<5>>,
    l_wait: Signal<Local, Bit>,
    l_busy: Signal<Local, Bit>,
    l_txact: Signal<Local, Bit>,
    l_enter_rm: Signal<Local, Bit>,
    l_abort: Signal<Local, Bit>,
    l_recover: Signal<Local, Bit>,
    l_txok: Signal<Local, Bit>,
    l_txfail: Signal<Local, Bit>,
    l_txrel: Signal<Local, Bit>,
    l_tx_ide: Signal<Local, Bit>,
    l_tx_rtr: Signal<Local, Bit>,
    l_tx_id: Signal<Local, Bits<29>>,
    l_tx_data: Signal<Local, Bits<64>>,
    // writer source
    l_stx: Signal<Local, Bit>,
    l_srx: Signal<Local, Bit>,
    l_srctx: Signal<Local, Bit>,
    l_s_ide: Signal<Local, Bit>,
    l_s_rtr: Signal<Local, Bit>,
    l_s_id: Signal<Local, Bits<29>>,
    l_s_dlc: Signal<Local, Bits<4>>,
    l_s_data: Signal<Local, Bits<64>>,
    l_s_n: Signal<Local, Bits<4>>,
    l_s_len: Signal<Local, Bits<4>>,
    l_msg: Signal<Local, Bits<104>>,
    l_wbyte: Signal<Local, Bits<8>>,
    l_wdone: Signal<Local, Bit>,
    l_fits: Signal<Local, Bit>,
    // filter
    l_acr: Signal<Local, Bits<32>>,
    l_amr: Signal<Local, Bits<32>>,
    l_v1: Signal<Local, Bits<32>>,
    l_v2: Signal<Local, Bits<32>>,
    l_m1: Signal<Local, Bits<32>>,
    l_m2: Signal<Local, Bits<32>>,
    l_acc: Signal<Local, Bit>,
    // FIFO release
    l_fi: Signal<Local, Bits<8>>,
    l_cur_n: Signal<Local, Bits<4>>,
    l_cur_len: Signal<Local, Bits<4>>,
    l_rrb: Signal<Local, Bit>,
    // ECC
    l_seg: Signal<Local, Bits<5>>,
    l_ecode: Signal<Local, Bits<8>>,
    l_pos: Signal<Local, Bits<8>>,
    // bit timing
    l_t1: Signal<Local, Bits<6>>,
    l_t2: Signal<Local, Bits<6>>,
    l_s: Signal<Local, Bits<6>>,
    l_prop: Signal<Local, Bits<6>>,
    l_ph1: Signal<Local, Bits<6>>,
    l_sjw: Signal<Local, Bits<6>>,
}

impl Sja1000 {
    /// A new register block (hold `rst` high for a clock to initialise it).
    /// A hardware reset clears BTR0 and BTR1.
    pub fn new() -> Self {
        Self {
            // zero-initialised FIFO RAM (block RAM initial contents)
            ram: (0..64).map(|_| Bits::<8>::from(0u64)).into(),
            ..Default::default()
        }
    }

    /// As [`Sja1000::new`], with the values a hardware reset loads into BTR0
    /// and BTR1 (a real SJA1000 leaves them undefined), so that the
    /// controller runs at a chosen bit rate from power-up.
    pub fn with_reset_timing(btr0: u8, btr1: u8) -> Self {
        Self { btr_reset: BtrReset::new(btr0, btr1), ..Self::new() }
    }

    /// The wrapped CAN core (read-only, for tests and debugging: e.g. its
    /// `dbg_sample` strobe and `state`).
    pub fn core(&self) -> &CanCore {
        &self.core
    }
}

impl Logic for Sja1000 {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self, clock, ack, rdat, ramsel, opm, lom, stm, afm, sleep, boff, core_bs, ier, ir, btr0, btr1, ocr, ewl,
            cdr, alc, alc_lock, ecc, ecc_lock, acr0, acr1, acr2, acr3, amr0, amr1, amr2, amr3,
            txb0, txb1, txb2, txb3, txb4, txb5, txb6, txb7, txb8, txb9, txb10, txb11, txb12, tx_pend, tx_single,
            tx_srr, tx_abrt, tx_lb, tcs_n, dos, rbsa, used, rmc, wr_busy, wr_src, wr_idx, wr_len, fetch_q, fetch_a,
            cur_fi, es_q, bs_q, pas_q, seen_ext
        );
        self.ram.read_clock.next = self.clock.val();
        self.ram.write_clock.next = self.clock.val();

        // ------------------------------------------------------------------
        // Bus interface decode.
        self.l_req.next = self.wb_cyc.val() & self.wb_stb.val() & !self.ack.q.val();
        self.l_wr.next = self.l_req.val() & self.wb_we.val();
        self.l_rd.next = self.l_req.val() & !self.wb_we.val();
        self.l_a.next = self.wb_adr.val().get_bits::<7>(0);
        self.l_d.next = self.wb_dat_w.val();
        self.l_rm.next = !self.opm.q.val();
        self.l_win.next = (self.l_a.val() >= 16) & (self.l_a.val() <= 28);
        self.l_aoff.next = self.l_a.val() - 32;

        // ------------------------------------------------------------------
        // Core status views.
        self.l_fld.next = self.core.dbg_field.val();
        // Reset mode proper (not the bus-off hold): the core is held in reset
        // with its counters loaded, and the status bits are frozen.
        self.l_frz.next = !self.opm.q.val() & !self.boff.q.val();
        self.l_cbsr.next = self.core.state.val() == 2;
        self.l_wait.next = (self.l_fld.val() == 0) | (self.l_fld.val() == 1) | (self.l_fld.val() == 3);
        self.l_busy.next = self.l_fld.val() >= 4;
        self.l_txact.next = self.core.dbg_role.val() & (self.l_fld.val() >= 4) & (self.l_fld.val() <= 17);
        // Visible error counters: the core's (a loaded bus-off, TEC 256,
        // reads 255); while bus-off 127 - completed recovery runs and 0.
        self.l_tecv.next = self.core.tec.val().get_bits::<8>(0);
        if self.core.tec.val().get_bit(8) {
            self.l_tecv.next = 255.into();
        }
        self.l_recv.next = self.core.rec.val();
        if self.l_cbsr.val() & !self.l_frz.val() {
            self.l_tecv.next = 127 - self.core.dbg_runs.val();
            self.l_recv.next = 0.into();
        }
        self.l_cbs.next = self.l_cbsr.val();
        self.l_es.next =
            self.l_cbsr.val() | (self.l_tecv.val() >= self.ewl.q.val()) | (self.l_recv.val() >= self.ewl.q.val());
        self.l_pas.next = !self.l_cbsr.val() & ((self.l_tecv.val() >= 128) | (self.l_recv.val() >= 128));
        if self.l_frz.val() {
            self.l_cbs.next = self.bs_q.q.val();
            self.l_es.next = self.es_q.q.val();
            self.l_pas.next = self.pas_q.q.val();
        }
        // Counter load: every clock in reset mode (the core holds its own
        // values, or takes a host write) and while the timing is rejected.
        self.l_cload.next = self.l_frz.val() | self.core.cfg_err.val();
        self.l_tecin.next = self.core.tec.val();
        self.l_recin.next = self.core.rec.val();

        // ------------------------------------------------------------------
        // TX buffer as the core's native request.
        self.l_tx_ide.next = self.txb0.q.val().get_bit(7);
        self.l_tx_rtr.next = self.txb0.q.val().get_bit(6);
        if self.l_tx_ide.val() {
            self.l_tx_id.next = (bit_cast::<29, 8>(self.txb1.q.val()) << 21)
                | (bit_cast::<29, 8>(self.txb2.q.val()) << 13)
                | (bit_cast::<29, 8>(self.txb3.q.val()) << 5)
                | (bit_cast::<29, 8>(self.txb4.q.val()) >> 3);
            self.l_tx_data.next = (bit_cast::<64, 8>(self.txb5.q.val()) << 56)
                | (bit_cast::<64, 8>(self.txb6.q.val()) << 48)
                | (bit_cast::<64, 8>(self.txb7.q.val()) << 40)
                | (bit_cast::<64, 8>(self.txb8.q.val()) << 32)
                | (bit_cast::<64, 8>(self.txb9.q.val()) << 24)
                | (bit_cast::<64, 8>(self.txb10.q.val()) << 16)
                | (bit_cast::<64, 8>(self.txb11.q.val()) << 8)
                | bit_cast::<64, 8>(self.txb12.q.val());
        } else {
            self.l_tx_id.next =
                (bit_cast::<29, 8>(self.txb1.q.val()) << 3) | (bit_cast::<29, 8>(self.txb2.q.val()) >> 5);
            self.l_tx_data.next = (bit_cast::<64, 8>(self.txb3.q.val()) << 56)
                | (bit_cast::<64, 8>(self.txb4.q.val()) << 48)
                | (bit_cast::<64, 8>(self.txb5.q.val()) << 40)
                | (bit_cast::<64, 8>(self.txb6.q.val()) << 32)
                | (bit_cast::<64, 8>(self.txb7.q.val()) << 24)
                | (bit_cast::<64, 8>(self.txb8.q.val()) << 16)
                | (bit_cast::<64, 8>(self.txb9.q.val()) << 8)
                | bit_cast::<64, 8>(self.txb10.q.val());
        }

        // ------------------------------------------------------------------
        // Bit timing: SJA1000 BTR0/BTR1 onto the core's fields (value - 1).
        // TQ = 2 (BRP + 1) clocks: the core's prescaler field is 2 BRP + 1.
        self.core.brp.next = (bit_cast::<7, 6>(self.btr0.q.val().get_bits::<6>(0)) << 1) | 1;
        // t1 = TSEG1 + 1 (1..16), t2 = TSEG2 + 1 (1..8), bit = 1 + t1 + t2.
        self.l_t1.next = bit_cast::<6, 4>(self.btr1.q.val().get_bits::<4>(0)) + 1;
        self.l_t2.next = bit_cast::<6, 3>(self.btr1.q.val().get_bits::<3>(4)) + 1;
        self.l_s.next = self.l_t1.val() + self.l_t2.val();
        // exact: PH1 = PH2 = t2, PROP = t1 - t2 (t1 > t2 >= 2)
        self.l_ph1.next = self.l_t2.val();
        self.l_prop.next = self.l_t1.val() - self.l_t2.val();
        if self.l_t2.val() == 1 {
            // PH2 is at least 2: keep the bit time, sample point 1 TQ earlier
            self.l_ph1.next = 1.into();
            self.l_prop.next = self.l_t1.val() - 2;
        } else if self.l_t1.val() <= self.l_t2.val() {
            // keep the bit time and PH2 = PH1, sample point later
            self.l_ph1.next = (self.l_s.val() - 1) >> 1;
            self.l_prop.next = self.l_s.val() - (self.l_ph1.val() << 1);
        }
        if self.l_s.val() < 7 {
            // under 8 TQ: a setting the core rejects
            self.l_prop.next = 1.into();
            self.l_ph1.next = 1.into();
        }
        self.l_sjw.next = bit_cast::<6, 2>(self.btr0.q.val().get_bits::<2>(6)) + 1;
        if self.l_sjw.val() > self.l_ph1.val() {
            self.l_sjw.next = self.l_ph1.val();
        }
        self.l_prop.next = self.l_prop.val() - 1;
        self.l_ph1.next = self.l_ph1.val() - 1;
        self.l_sjw.next = self.l_sjw.val() - 1;
        self.core.prop.next = self.l_prop.val().get_bits::<4>(0);
        self.core.ph1.next = self.l_ph1.val().get_bits::<3>(0);
        self.core.sjw.next = self.l_sjw.val().get_bits::<2>(0);
        self.core.triple.next = self.btr1.q.val().get_bit(7);

        // ------------------------------------------------------------------
        // Frame source of the FIFO writer: the core's delivery or (self
        // reception) the TX buffer.
        self.l_txok.next = self.tx_pend.q.val() & self.core.tx_done.val();
        self.l_stx.next = self.l_txok.val() & self.tx_srr.q.val() & self.opm.q.val();
        self.l_srx.next = self.core.rx_valid.val() & self.opm.q.val();
        self.l_srctx.next = self.l_stx.val();
        if self.wr_busy.q.val() {
            self.l_srctx.next = self.wr_src.q.val();
        }
        self.l_s_ide.next = self.core.rx_ide.val();
        self.l_s_rtr.next = self.core.rx_rtr.val();
        self.l_s_id.next = self.core.rx_id.val();
        self.l_s_dlc.next = self.core.rx_dlc.val();
        self.l_s_data.next = self.core.rx_data.val();
        if self.l_srctx.val() {
            self.l_s_ide.next = self.l_tx_ide.val();
            self.l_s_rtr.next = self.l_tx_rtr.val();
            self.l_s_id.next = self.l_tx_id.val();
            self.l_s_dlc.next = self.txb0.q.val().get_bits::<4>(0);
            self.l_s_data.next = self.l_tx_data.val();
        }
        if !self.l_s_ide.val() {
            self.l_s_id.next = self.l_s_id.val() & 0x7FF;
        }
        self.l_s_n.next = self.l_s_dlc.val();
        if self.l_s_dlc.val().get_bit(3) {
            self.l_s_n.next = 8.into();
        }
        if self.l_s_rtr.val() {
            self.l_s_n.next = 0.into();
        }
        self.l_s_len.next = self.l_s_n.val() + 3;
        if self.l_s_ide.val() {
            self.l_s_len.next = self.l_s_n.val() + 5;
        }
        // The message as stored: FI, identifier bytes, data (13 bytes, FI first).
        self.l_msg.next = (bit_cast::<104, 4>(self.l_s_dlc.val()) << 96) | (bit_cast::<104, 64>(self.l_s_data.val()) << 16);
        self.l_msg.next = self.l_msg.val().replace_bit(102, self.l_s_rtr.val());
        if self.l_s_ide.val() {
            self.l_msg.next = (bit_cast::<104, 4>(self.l_s_dlc.val()) << 96)
                | (bit_cast::<104, 29>(self.l_s_id.val()) << 67)
                | bit_cast::<104, 64>(self.l_s_data.val());
            self.l_msg.next = self.l_msg.val().replace_bit(103, true);
            self.l_msg.next = self.l_msg.val().replace_bit(102, self.l_s_rtr.val());
            self.l_msg.next = self.l_msg.val().replace_bit(66, self.l_s_rtr.val());
        } else {
            self.l_msg.next = self.l_msg.val() | (bit_cast::<104, 29>(self.l_s_id.val()) << 85);
            self.l_msg.next = self.l_msg.val().replace_bit(84, self.l_s_rtr.val());
        }

        // ------------------------------------------------------------------
        // Acceptance filter on the source frame.
        self.l_acr.next = (bit_cast::<32, 8>(self.acr0.q.val()) << 24)
            | (bit_cast::<32, 8>(self.acr1.q.val()) << 16)
            | (bit_cast::<32, 8>(self.acr2.q.val()) << 8)
            | bit_cast::<32, 8>(self.acr3.q.val());
        self.l_amr.next = (bit_cast::<32, 8>(self.amr0.q.val()) << 24)
            | (bit_cast::<32, 8>(self.amr1.q.val()) << 16)
            | (bit_cast::<32, 8>(self.amr2.q.val()) << 8)
            | bit_cast::<32, 8>(self.amr3.q.val());
        if self.afm.q.val() {
            // single filter
            if self.l_s_ide.val() {
                self.l_v1.next = bit_cast::<32, 29>(self.l_s_id.val()) << 3;
                self.l_v1.next = self.l_v1.val().replace_bit(2, self.l_s_rtr.val());
                self.l_m1.next = self.l_amr.val() | 3;
            } else {
                self.l_v1.next = (bit_cast::<32, 11>(self.l_s_id.val().get_bits::<11>(0)) << 21)
                    | bit_cast::<32, 16>(self.l_s_data.val().get_bits::<16>(48));
                self.l_v1.next = self.l_v1.val().replace_bit(20, self.l_s_rtr.val());
                self.l_m1.next = self.l_amr.val() | 0x000F_0000;
                if self.l_s_n.val() < 2 {
                    self.l_m1.next = self.l_m1.val() | 0xFF;
                }
                if self.l_s_n.val() < 1 {
                    self.l_m1.next = self.l_m1.val() | 0xFF00;
                }
            }
            self.l_v2.next = 0.into();
            self.l_m2.next = 0.into();
            self.l_acc.next = ((self.l_v1.val() ^ self.l_acr.val()) & !self.l_m1.val()) == 0;
        } else {
            // dual filter
            if self.l_s_ide.val() {
                self.l_v1.next = bit_cast::<32, 16>(self.l_s_id.val().get_bits::<16>(13)) << 16;
                self.l_m1.next = self.l_amr.val() | 0xFFFF;
                self.l_v2.next = bit_cast::<32, 16>(self.l_s_id.val().get_bits::<16>(13));
                self.l_m2.next = self.l_amr.val() | 0xFFFF_0000_u64;
            } else {
                self.l_v1.next = (bit_cast::<32, 11>(self.l_s_id.val().get_bits::<11>(0)) << 21)
                    | (bit_cast::<32, 4>(self.l_s_data.val().get_bits::<4>(60)) << 16)
                    | bit_cast::<32, 4>(self.l_s_data.val().get_bits::<4>(56));
                self.l_v1.next = self.l_v1.val().replace_bit(20, self.l_s_rtr.val());
                self.l_m1.next = self.l_amr.val() | 0xFFF0;
                if self.l_s_n.val() < 1 {
                    self.l_m1.next = self.l_m1.val() | 0x000F_000F;
                }
                self.l_v2.next = bit_cast::<32, 11>(self.l_s_id.val().get_bits::<11>(0)) << 5;
                self.l_v2.next = self.l_v2.val().replace_bit(4, self.l_s_rtr.val());
                self.l_m2.next = self.l_amr.val() | 0xFFFF_000F_u64;
            }
            self.l_acc.next = (((self.l_v1.val() ^ self.l_acr.val()) & !self.l_m1.val()) == 0)
                | (((self.l_v2.val() ^ self.l_acr.val()) & !self.l_m2.val()) == 0);
        }

        // ------------------------------------------------------------------
        // Message length of the message at RBSA (for RRB).
        self.l_fi.next = self.cur_fi.q.val();
        if self.fetch_q.q.val() & (self.fetch_a.q.val() == self.rbsa.q.val()) {
            self.l_fi.next = self.ram.read_data.val();
        }
        self.cur_fi.d.next = self.l_fi.val();
        self.l_cur_n.next = self.l_fi.val().get_bits::<4>(0);
        if self.l_fi.val().get_bit(3) {
            self.l_cur_n.next = 8.into();
        }
        if self.l_fi.val().get_bit(6) {
            self.l_cur_n.next = 0.into();
        }
        self.l_cur_len.next = self.l_cur_n.val() + 3;
        if self.l_fi.val().get_bit(7) {
            self.l_cur_len.next = self.l_cur_n.val() + 5;
        }

        // ------------------------------------------------------------------
        // Writer byte.
        self.l_wbyte.next = self.l_msg.val().get_bits::<8>(96);
        if self.wr_idx.q.val() == 1 {
            self.l_wbyte.next = self.l_msg.val().get_bits::<8>(88);
        }
        if self.wr_idx.q.val() == 2 {
            self.l_wbyte.next = self.l_msg.val().get_bits::<8>(80);
        }
        if self.wr_idx.q.val() == 3 {
            self.l_wbyte.next = self.l_msg.val().get_bits::<8>(72);
        }
        if self.wr_idx.q.val() == 4 {
            self.l_wbyte.next = self.l_msg.val().get_bits::<8>(64);
        }
        if self.wr_idx.q.val() == 5 {
            self.l_wbyte.next = self.l_msg.val().get_bits::<8>(56);
        }
        if self.wr_idx.q.val() == 6 {
            self.l_wbyte.next = self.l_msg.val().get_bits::<8>(48);
        }
        if self.wr_idx.q.val() == 7 {
            self.l_wbyte.next = self.l_msg.val().get_bits::<8>(40);
        }
        if self.wr_idx.q.val() == 8 {
            self.l_wbyte.next = self.l_msg.val().get_bits::<8>(32);
        }
        if self.wr_idx.q.val() == 9 {
            self.l_wbyte.next = self.l_msg.val().get_bits::<8>(24);
        }
        if self.wr_idx.q.val() == 10 {
            self.l_wbyte.next = self.l_msg.val().get_bits::<8>(16);
        }
        if self.wr_idx.q.val() == 11 {
            self.l_wbyte.next = self.l_msg.val().get_bits::<8>(8);
        }
        if self.wr_idx.q.val() == 12 {
            self.l_wbyte.next = self.l_msg.val().get_bits::<8>(0);
        }
        self.l_wdone.next = self.wr_busy.q.val() & ((self.wr_idx.q.val() + 1) == self.wr_len.q.val());
        self.l_fits.next = (self.used.q.val() + bit_cast::<7, 4>(self.l_s_len.val())) <= 64;

        // ------------------------------------------------------------------
        // Register defaults.
        self.ack.d.next = self.l_req.val();
        self.rdat.d.next = self.rdat.q.val();
        self.ramsel.d.next = self.ramsel.q.val();
        self.opm.d.next = self.opm.q.val();
        self.lom.d.next = self.lom.q.val();
        self.stm.d.next = self.stm.q.val();
        self.afm.d.next = self.afm.q.val();
        self.sleep.d.next = self.sleep.q.val();
        self.boff.d.next = self.boff.q.val();
        self.core_bs.d.next = self.l_cbsr.val() & !self.l_frz.val();
        self.ier.d.next = self.ier.q.val();
        self.ir.d.next = self.ir.q.val();
        self.l_irn.next = self.ir.q.val();
        self.btr0.d.next = self.btr0.q.val();
        self.btr1.d.next = self.btr1.q.val();
        self.ocr.d.next = self.ocr.q.val();
        self.ewl.d.next = self.ewl.q.val();
        self.cdr.d.next = self.cdr.q.val();
        self.alc.d.next = self.alc.q.val();
        self.alc_lock.d.next = self.alc_lock.q.val();
        self.ecc.d.next = self.ecc.q.val();
        self.ecc_lock.d.next = self.ecc_lock.q.val();
        self.acr0.d.next = self.acr0.q.val();
        self.acr1.d.next = self.acr1.q.val();
        self.acr2.d.next = self.acr2.q.val();
        self.acr3.d.next = self.acr3.q.val();
        self.amr0.d.next = self.amr0.q.val();
        self.amr1.d.next = self.amr1.q.val();
        self.amr2.d.next = self.amr2.q.val();
        self.amr3.d.next = self.amr3.q.val();
        self.txb0.d.next = self.txb0.q.val();
        self.txb1.d.next = self.txb1.q.val();
        self.txb2.d.next = self.txb2.q.val();
        self.txb3.d.next = self.txb3.q.val();
        self.txb4.d.next = self.txb4.q.val();
        self.txb5.d.next = self.txb5.q.val();
        self.txb6.d.next = self.txb6.q.val();
        self.txb7.d.next = self.txb7.q.val();
        self.txb8.d.next = self.txb8.q.val();
        self.txb9.d.next = self.txb9.q.val();
        self.txb10.d.next = self.txb10.q.val();
        self.txb11.d.next = self.txb11.q.val();
        self.txb12.d.next = self.txb12.q.val();
        self.tx_pend.d.next = self.tx_pend.q.val();
        self.tx_single.d.next = self.tx_single.q.val();
        self.tx_srr.d.next = self.tx_srr.q.val();
        self.tx_abrt.d.next = self.tx_abrt.q.val();
        self.tx_lb.d.next = self.tx_lb.q.val();
        self.tcs_n.d.next = self.tcs_n.q.val();
        self.dos.d.next = self.dos.q.val();
        self.rbsa.d.next = self.rbsa.q.val();
        self.used.d.next = self.used.q.val();
        self.rmc.d.next = self.rmc.q.val();
        self.wr_busy.d.next = self.wr_busy.q.val();
        self.wr_src.d.next = self.wr_src.q.val();
        self.wr_idx.d.next = self.wr_idx.q.val();
        self.wr_len.d.next = self.wr_len.q.val();
        self.es_q.d.next = self.l_es.val();
        self.bs_q.d.next = self.l_cbs.val();
        self.pas_q.d.next = self.l_pas.val();
        self.seen_ext.d.next = self.seen_ext.q.val();
        if self.l_fld.val() == 9 {
            self.seen_ext.d.next = true;
        }
        if self.l_fld.val() == 4 {
            self.seen_ext.d.next = false;
        }
        self.l_ev.next = 0.into();
        self.l_enter_rm.next = false;
        self.l_abort.next = false;
        self.l_recover.next = false;
        self.l_rrb.next = false;
        self.l_txrel.next = false;

        // ------------------------------------------------------------------
        // Status register.
        self.l_sr.next = 0.into();
        self.l_sr.next = self.l_sr.val().replace_bit(0, self.rmc.q.val() != 0);
        self.l_sr.next = self.l_sr.val().replace_bit(1, self.dos.q.val());
        self.l_tbs.next = !self.tx_pend.q.val();
        self.l_tcs.next = !self.tcs_n.q.val();
        self.l_sr.next = self.l_sr.val().replace_bit(2, self.l_tbs.val());
        self.l_sr.next = self.l_sr.val().replace_bit(3, self.l_tcs.val());
        self.l_sr.next = self
            .l_sr
            .val()
            .replace_bit(4, self.l_wait.val() | (self.l_busy.val() & !self.core.dbg_role.val()));
        self.l_sr.next = self
            .l_sr
            .val()
            .replace_bit(5, self.l_wait.val() | (self.l_busy.val() & self.core.dbg_role.val()));
        self.l_sr.next = self.l_sr.val().replace_bit(6, self.l_es.val());
        self.l_sr.next = self.l_sr.val().replace_bit(7, self.l_cbs.val());
        // Interrupt register as read: latched bits plus RI (level).
        self.l_irv.next = self.ir.q.val().replace_bit(0, self.ier.q.val().get_bit(0) & (self.rmc.q.val() != 0));

        // ------------------------------------------------------------------
        // Read data.
        self.l_ramrd.next = false;
        self.l_rdv.next = 0.into();
        if self.l_a.val() == 0 {
            self.l_rdv.next = self.l_rdv.val().replace_bit(0, self.l_rm.val());
            self.l_rdv.next = self.l_rdv.val().replace_bit(1, self.lom.q.val());
            self.l_rdv.next = self.l_rdv.val().replace_bit(2, self.stm.q.val());
            self.l_rdv.next = self.l_rdv.val().replace_bit(3, self.afm.q.val());
            self.l_rdv.next = self.l_rdv.val().replace_bit(4, self.sleep.q.val());
        }
        if self.l_a.val() == 2 {
            self.l_rdv.next = self.l_sr.val();
        }
        if self.l_a.val() == 3 {
            self.l_rdv.next = self.l_irv.val();
        }
        if self.l_a.val() == 4 {
            self.l_rdv.next = self.ier.q.val();
        }
        if self.l_a.val() == 6 {
            self.l_rdv.next = self.btr0.q.val();
        }
        if self.l_a.val() == 7 {
            self.l_rdv.next = self.btr1.q.val();
        }
        if self.l_a.val() == 8 {
            self.l_rdv.next = self.ocr.q.val();
        }
        if self.l_a.val() == 11 {
            self.l_rdv.next = bit_cast::<8, 5>(self.alc.q.val());
        }
        if self.l_a.val() == 12 {
            self.l_rdv.next = self.ecc.q.val();
        }
        if self.l_a.val() == 13 {
            self.l_rdv.next = self.ewl.q.val();
        }
        if self.l_a.val() == 14 {
            self.l_rdv.next = self.l_recv.val();
        }
        if self.l_a.val() == 15 {
            self.l_rdv.next = self.l_tecv.val();
        }
        if self.l_rm.val() {
            if self.l_a.val() == 16 {
                self.l_rdv.next = self.acr0.q.val();
            }
            if self.l_a.val() == 17 {
                self.l_rdv.next = self.acr1.q.val();
            }
            if self.l_a.val() == 18 {
                self.l_rdv.next = self.acr2.q.val();
            }
            if self.l_a.val() == 19 {
                self.l_rdv.next = self.acr3.q.val();
            }
            if self.l_a.val() == 20 {
                self.l_rdv.next = self.amr0.q.val();
            }
            if self.l_a.val() == 21 {
                self.l_rdv.next = self.amr1.q.val();
            }
            if self.l_a.val() == 22 {
                self.l_rdv.next = self.amr2.q.val();
            }
            if self.l_a.val() == 23 {
                self.l_rdv.next = self.amr3.q.val();
            }
        } else if self.l_win.val() {
            self.l_ramrd.next = true;
        }
        if self.l_a.val() == 29 {
            self.l_rdv.next = bit_cast::<8, 5>(self.rmc.q.val());
        }
        if self.l_a.val() == 30 {
            self.l_rdv.next = bit_cast::<8, 6>(self.rbsa.q.val());
        }
        if self.l_a.val() == 31 {
            self.l_rdv.next = self.cdr.q.val();
        }
        if (self.l_a.val() >= 32) & (self.l_a.val() < 96) {
            self.l_ramrd.next = true;
        }
        if self.l_a.val() == 96 {
            self.l_rdv.next = self.txb0.q.val();
        }
        if self.l_a.val() == 97 {
            self.l_rdv.next = self.txb1.q.val();
        }
        if self.l_a.val() == 98 {
            self.l_rdv.next = self.txb2.q.val();
        }
        if self.l_a.val() == 99 {
            self.l_rdv.next = self.txb3.q.val();
        }
        if self.l_a.val() == 100 {
            self.l_rdv.next = self.txb4.q.val();
        }
        if self.l_a.val() == 101 {
            self.l_rdv.next = self.txb5.q.val();
        }
        if self.l_a.val() == 102 {
            self.l_rdv.next = self.txb6.q.val();
        }
        if self.l_a.val() == 103 {
            self.l_rdv.next = self.txb7.q.val();
        }
        if self.l_a.val() == 104 {
            self.l_rdv.next = self.txb8.q.val();
        }
        if self.l_a.val() == 105 {
            self.l_rdv.next = self.txb9.q.val();
        }
        if self.l_a.val() == 106 {
            self.l_rdv.next = self.txb10.q.val();
        }
        if self.l_a.val() == 107 {
            self.l_rdv.next = self.txb11.q.val();
        }
        if self.l_a.val() == 108 {
            self.l_rdv.next = self.txb12.q.val();
        }
        // RAM read port: the host, else the fetch of the frame info at RBSA.
        self.ram.read_address.next = self.rbsa.q.val();
        self.fetch_q.d.next = true;
        if self.l_rd.val() & self.l_ramrd.val() {
            self.fetch_q.d.next = false;
            if self.l_win.val() {
                self.ram.read_address.next = self.rbsa.q.val() + (self.l_a.val().get_bits::<6>(0) - 16);
            } else {
                self.ram.read_address.next = self.l_aoff.val().get_bits::<6>(0);
            }
        }
        self.fetch_a.d.next = self.rbsa.q.val();
        if self.l_rd.val() {
            self.rdat.d.next = self.l_rdv.val();
            self.ramsel.d.next = self.l_ramrd.val();
            if self.l_a.val() == 3 {
                self.l_irn.next = 0.into();
            }
            if self.l_a.val() == 11 {
                self.alc_lock.d.next = false;
            }
            if self.l_a.val() == 12 {
                self.ecc_lock.d.next = false;
            }
        }

        // ------------------------------------------------------------------
        // Writes.
        self.ram.write_address.next = self.l_aoff.val().get_bits::<6>(0);
        self.ram.write_data.next = self.l_d.val();
        self.ram.write_enable.next = false;
        if self.l_wr.val() {
            if self.l_a.val() == 0 {
                if self.l_rm.val() {
                    self.lom.d.next = self.l_d.val().get_bit(1);
                    self.stm.d.next = self.l_d.val().get_bit(2);
                    self.afm.d.next = self.l_d.val().get_bit(3);
                    if !self.l_d.val().get_bit(0) {
                        self.opm.d.next = true;
                        self.l_recover.next = self.boff.q.val();
                    }
                } else if self.l_d.val().get_bit(0) {
                    self.l_enter_rm.next = true;
                } else if self.l_d.val().get_bit(4) {
                    if !self.sleep.q.val()
                        & (self.l_irv.val() == 0)
                        & (self.l_fld.val() == 2)
                        & !self.tx_pend.q.val()
                    {
                        self.sleep.d.next = true;
                    }
                } else if self.sleep.q.val() {
                    self.sleep.d.next = false;
                    self.l_ev.next = self.l_ev.val().replace_bit(4, true);
                }
            }
            if self.l_a.val() == 1 {
                if self.opm.q.val() {
                    if (self.l_d.val().get_bit(0) | self.l_d.val().get_bit(4))
                        & !self.tx_pend.q.val()
                        & !self.sleep.q.val()
                    {
                        self.tx_pend.d.next = true;
                        self.tx_single.d.next = self.l_d.val().get_bit(1);
                        self.tx_srr.d.next = self.l_d.val().get_bit(4);
                        self.tx_abrt.d.next = false;
                    } else if self.l_d.val().get_bit(1) & self.tx_pend.q.val() & !self.tx_lb.q.val() {
                        self.l_abort.next = true;
                        self.tx_abrt.d.next = true;
                    }
                }
                if self.l_d.val().get_bit(2) & (self.rmc.q.val() != 0) {
                    self.l_rrb.next = true;
                }
                if self.l_d.val().get_bit(3) {
                    self.dos.d.next = false;
                }
            }
            if self.l_a.val() == 4 {
                self.ier.d.next = self.l_d.val();
            }
            if self.l_a.val() == 31 {
                self.cdr.d.next = (self.cdr.q.val() & 0xE0) | (self.l_d.val() & 0x0F);
                if self.l_rm.val() {
                    self.cdr.d.next = self.l_d.val() & 0xEF;
                }
            }
            if self.l_rm.val() {
                if self.l_a.val() == 6 {
                    self.btr0.d.next = self.l_d.val();
                }
                if self.l_a.val() == 7 {
                    self.btr1.d.next = self.l_d.val();
                }
                if self.l_a.val() == 8 {
                    self.ocr.d.next = self.l_d.val();
                }
                if self.l_a.val() == 13 {
                    self.ewl.d.next = self.l_d.val();
                }
                if (self.l_a.val() == 14) & self.l_frz.val() {
                    // (no effect while bus-off)
                    self.l_cload.next = true;
                    self.l_recin.next = self.l_d.val();
                }
                if self.l_a.val() == 15 {
                    // 255: CPU-driven bus-off when reset mode is left
                    self.l_cload.next = true;
                    self.l_tecin.next = bit_cast::<9, 8>(self.l_d.val());
                    if self.l_d.val() == 255 {
                        self.l_tecin.next = 256.into();
                    }
                    if self.boff.q.val() {
                        // ends the bus-off hold: the core restarts from the
                        // written value (integration of 11 recessive bits)
                        self.boff.d.next = false;
                        self.l_recin.next = 0.into();
                        if self.l_d.val() != 255 {
                            self.bs_q.d.next = false;
                        }
                    }
                }
                if self.l_a.val() == 16 {
                    self.acr0.d.next = self.l_d.val();
                }
                if self.l_a.val() == 17 {
                    self.acr1.d.next = self.l_d.val();
                }
                if self.l_a.val() == 18 {
                    self.acr2.d.next = self.l_d.val();
                }
                if self.l_a.val() == 19 {
                    self.acr3.d.next = self.l_d.val();
                }
                if self.l_a.val() == 20 {
                    self.amr0.d.next = self.l_d.val();
                }
                if self.l_a.val() == 21 {
                    self.amr1.d.next = self.l_d.val();
                }
                if self.l_a.val() == 22 {
                    self.amr2.d.next = self.l_d.val();
                }
                if self.l_a.val() == 23 {
                    self.amr3.d.next = self.l_d.val();
                }
                if self.l_a.val() == 30 {
                    self.rbsa.d.next = self.l_d.val().get_bits::<6>(0);
                    self.used.d.next = 0.into();
                    self.rmc.d.next = 0.into();
                }
                if (self.l_a.val() >= 32) & (self.l_a.val() < 96) {
                    self.ram.write_enable.next = true;
                }
            }
            // TX buffer: 0x10.. in operating mode (TBS = 1), 0x60.. in reset mode.
            if (self.opm.q.val() & self.l_win.val() & !self.tx_pend.q.val())
                | (self.l_rm.val() & (self.l_a.val() >= 96) & (self.l_a.val() <= 108))
            {
                if self.l_a.val().get_bits::<4>(0) == 0 {
                    self.txb0.d.next = self.l_d.val();
                }
                if self.l_a.val().get_bits::<4>(0) == 1 {
                    self.txb1.d.next = self.l_d.val();
                }
                if self.l_a.val().get_bits::<4>(0) == 2 {
                    self.txb2.d.next = self.l_d.val();
                }
                if self.l_a.val().get_bits::<4>(0) == 3 {
                    self.txb3.d.next = self.l_d.val();
                }
                if self.l_a.val().get_bits::<4>(0) == 4 {
                    self.txb4.d.next = self.l_d.val();
                }
                if self.l_a.val().get_bits::<4>(0) == 5 {
                    self.txb5.d.next = self.l_d.val();
                }
                if self.l_a.val().get_bits::<4>(0) == 6 {
                    self.txb6.d.next = self.l_d.val();
                }
                if self.l_a.val().get_bits::<4>(0) == 7 {
                    self.txb7.d.next = self.l_d.val();
                }
                if self.l_a.val().get_bits::<4>(0) == 8 {
                    self.txb8.d.next = self.l_d.val();
                }
                if self.l_a.val().get_bits::<4>(0) == 9 {
                    self.txb9.d.next = self.l_d.val();
                }
                if self.l_a.val().get_bits::<4>(0) == 10 {
                    self.txb10.d.next = self.l_d.val();
                }
                if self.l_a.val().get_bits::<4>(0) == 11 {
                    self.txb11.d.next = self.l_d.val();
                }
                if self.l_a.val().get_bits::<4>(0) == 12 {
                    self.txb12.d.next = self.l_d.val();
                }
            }
        }

        // ------------------------------------------------------------------
        // Transmission progress.
        self.l_txfail.next = self.tx_pend.q.val()
            & !self.tx_lb.q.val()
            & (self.tx_single.q.val() | self.tx_abrt.q.val())
            & (self.core.arb_lost.val() | (self.core.error.val() & self.core.err_tx.val()));
        if self.tx_pend.q.val()
            & self.tx_abrt.q.val()
            & !self.tx_lb.q.val()
            & !self.core.dbg_tx_rqst.val()
            & !self.l_txact.val()
            & !self.l_txok.val()
        {
            self.l_txfail.next = true;
        }
        if self.l_txok.val() {
            self.tcs_n.d.next = false;
            if self.tx_srr.q.val() {
                self.tx_lb.d.next = true;
            } else {
                self.l_txrel.next = true;
            }
        } else if self.l_txfail.val() {
            self.tcs_n.d.next = true;
            self.l_txrel.next = true;
        }

        // ------------------------------------------------------------------
        // FIFO writer.
        if self.wr_busy.q.val() {
            self.ram.write_address.next =
                (self.rbsa.q.val() + self.used.q.val().get_bits::<6>(0)) + bit_cast::<6, 4>(self.wr_idx.q.val());
            self.ram.write_data.next = self.l_wbyte.val();
            self.ram.write_enable.next = true;
            self.wr_idx.d.next = self.wr_idx.q.val() + 1;
            if self.l_wdone.val() {
                self.wr_busy.d.next = false;
                if self.wr_src.q.val() {
                    self.l_txrel.next = true;
                    self.tx_lb.d.next = false;
                }
            }
        }
        if self.l_srx.val() | self.l_stx.val() {
            if self.l_acc.val() & self.l_fits.val() & !self.wr_busy.q.val() {
                self.wr_busy.d.next = true;
                self.wr_src.d.next = self.l_stx.val();
                self.wr_idx.d.next = 0.into();
                self.wr_len.d.next = self.l_s_len.val();
            } else {
                if self.l_acc.val() {
                    self.dos.d.next = true;
                    if !self.dos.q.val() {
                        self.l_ev.next = self.l_ev.val().replace_bit(3, true);
                    }
                }
                if self.l_stx.val() {
                    self.l_txrel.next = true;
                    self.tx_lb.d.next = false;
                }
            }
        }
        // FIFO pointers.
        if self.l_rrb.val() {
            self.rbsa.d.next = self.rbsa.q.val() + bit_cast::<6, 4>(self.l_cur_len.val());
        }
        if self.l_wdone.val() & !self.l_rrb.val() {
            self.rmc.d.next = self.rmc.q.val() + 1;
            self.used.d.next = self.used.q.val() + bit_cast::<7, 4>(self.wr_len.q.val());
        } else if self.l_rrb.val() & !self.l_wdone.val() {
            self.rmc.d.next = self.rmc.q.val() - 1;
            self.used.d.next = self.used.q.val() - bit_cast::<7, 4>(self.l_cur_len.val());
        } else if self.l_rrb.val() & self.l_wdone.val() {
            self.used.d.next = (self.used.q.val() + bit_cast::<7, 4>(self.wr_len.q.val()))
                - bit_cast::<7, 4>(self.l_cur_len.val());
        }
        if self.l_txrel.val() {
            self.tx_pend.d.next = false;
            self.l_ev.next = self.l_ev.val().replace_bit(1, true);
        }

        // ------------------------------------------------------------------
        // Capture registers.
        self.l_alcm1.next = self.core.arb_lost_pos.val() - 1;
        if self.core.arb_lost.val() {
            self.l_ev.next = self.l_ev.val().replace_bit(6, true);
            if !self.alc_lock.q.val() {
                self.alc.d.next = self.l_alcm1.val().get_bits::<5>(0);
                self.alc_lock.d.next = true;
            }
        }
        self.l_pos.next = self.core.err_pos.val();
        self.l_seg.next = 0x12.into();
        if self.core.err_field.val() == 4 {
            self.l_seg.next = 0x03.into();
        }
        if self.core.err_field.val() == 5 {
            self.l_seg.next = 0x02.into();
            if self.l_pos.val() > 8 {
                self.l_seg.next = 0x06.into();
            }
        }
        if self.core.err_field.val() == 6 {
            self.l_seg.next = 0x04.into();
        }
        if self.core.err_field.val() == 7 {
            self.l_seg.next = 0x05.into();
        }
        if self.core.err_field.val() == 8 {
            self.l_seg.next = 0x04.into();
            if self.seen_ext.q.val() {
                self.l_seg.next = 0x0C.into();
            }
        }
        if self.core.err_field.val() == 9 {
            self.l_seg.next = 0x07.into();
            if self.l_pos.val() > 5 {
                self.l_seg.next = 0x0F.into();
            }
            if self.l_pos.val() > 13 {
                self.l_seg.next = 0x0E.into();
            }
        }
        if self.core.err_field.val() == 10 {
            self.l_seg.next = 0x09.into();
            if self.seen_ext.q.val() & (self.l_pos.val() == 1) {
                self.l_seg.next = 0x0D.into();
            }
        }
        if self.core.err_field.val() == 11 {
            self.l_seg.next = 0x0B.into();
        }
        if self.core.err_field.val() == 12 {
            self.l_seg.next = 0x0A.into();
        }
        if self.core.err_field.val() == 13 {
            self.l_seg.next = 0x08.into();
        }
        if self.core.err_field.val() == 14 {
            self.l_seg.next = 0x18.into();
        }
        if self.core.err_field.val() == 15 {
            self.l_seg.next = 0x19.into();
        }
        if self.core.err_field.val() == 16 {
            self.l_seg.next = 0x1B.into();
        }
        if self.core.err_field.val() == 17 {
            self.l_seg.next = 0x1A.into();
        }
        if self.core.err_field.val() == 18 {
            self.l_seg.next = 0x11.into();
        }
        if self.core.err_field.val() == 19 {
            self.l_seg.next = 0x16.into();
        }
        if self.core.err_field.val() == 20 {
            self.l_seg.next = 0x1C.into();
        }
        if (self.core.err_field.val() == 21) | (self.core.err_field.val() == 22) {
            self.l_seg.next = 0x17.into();
        }
        self.l_dirrx.next = !self.core.err_tx.val();
        self.l_ecode.next = 0xC0.into();
        if self.core.err_kind.val().get_bit(3) {
            self.l_ecode.next = 0x40.into();
        }
        if self.core.err_kind.val().get_bit(1) {
            self.l_ecode.next = 0x80.into();
        }
        if self.core.err_kind.val().get_bit(0) {
            self.l_ecode.next = 0x00.into();
        }
        self.l_ecode.next = (self.l_ecode.val() | bit_cast::<8, 5>(self.l_seg.val()))
            .replace_bit(5, self.l_dirrx.val());
        if self.core.error.val() {
            self.l_ev.next = self.l_ev.val().replace_bit(7, true);
            if !self.ecc_lock.q.val() {
                self.ecc.d.next = self.l_ecode.val();
                self.ecc_lock.d.next = true;
            }
        }

        // ------------------------------------------------------------------
        // Error state changes, bus-off, sleep wake-up.
        if self.l_es.val() != self.es_q.q.val() {
            self.l_ev.next = self.l_ev.val().replace_bit(2, true);
        }
        if self.l_cbs.val() != self.bs_q.q.val() {
            self.l_ev.next = self.l_ev.val().replace_bit(2, true);
        }
        if (self.l_pas.val() & !self.pas_q.q.val()) | (!self.l_pas.val() & self.pas_q.q.val() & !self.l_cbs.val()) {
            self.l_ev.next = self.l_ev.val().replace_bit(5, true);
        }
        if (self.l_cbsr.val() & !self.l_frz.val()) & !self.core_bs.q.val() {
            // bus-off: reset mode, core kept in its bus-off state
            self.boff.d.next = true;
            self.l_enter_rm.next = true;
            self.l_ev.next = self.l_ev.val().replace_bit(2, true);
        }
        if !self.l_cbsr.val() & self.core_bs.q.val() {
            self.boff.d.next = false;
        }
        if self.sleep.q.val() & self.core.dbg_sample.val() & !self.core.dbg_busmon.val() {
            self.sleep.d.next = false;
            self.l_ev.next = self.l_ev.val().replace_bit(4, true);
        }
        if self.l_enter_rm.val() {
            self.opm.d.next = false;
            self.tx_pend.d.next = false;
            self.tx_lb.d.next = false;
            self.tx_abrt.d.next = false;
            self.wr_busy.d.next = false;
            self.used.d.next = 0.into();
            self.rmc.d.next = 0.into();
            self.sleep.d.next = false;
            if self.sleep.q.val() {
                self.l_ev.next = self.l_ev.val().replace_bit(4, true);
            }
            self.l_ev.next = self.l_ev.val().replace_bit(1, false);
        }
        self.ir.d.next = self.l_irn.val() | (self.l_ev.val() & self.ier.q.val() & 0xFE);

        // ------------------------------------------------------------------
        // Hardware reset.
        if self.rst.val() {
            self.ack.d.next = false;
            self.opm.d.next = false;
            self.lom.d.next = false;
            self.stm.d.next = false;
            self.afm.d.next = false;
            self.sleep.d.next = false;
            self.boff.d.next = false;
            self.core_bs.d.next = false;
            self.es_q.d.next = false;
            self.bs_q.d.next = false;
            self.pas_q.d.next = false;
            self.ier.d.next = 0.into();
            self.ir.d.next = 0.into();
            self.btr0.d.next = self.btr_reset.btr0.val();
            self.btr1.d.next = self.btr_reset.btr1.val();
            self.ocr.d.next = 0.into();
            self.ewl.d.next = 96.into();
            self.cdr.d.next = 0.into();
            self.alc.d.next = 0.into();
            self.alc_lock.d.next = false;
            self.ecc.d.next = 0.into();
            self.ecc_lock.d.next = false;
            self.amr0.d.next = 0xFF.into();
            self.amr1.d.next = 0xFF.into();
            self.amr2.d.next = 0xFF.into();
            self.amr3.d.next = 0xFF.into();
            self.tx_pend.d.next = false;
            self.tx_lb.d.next = false;
            self.tx_abrt.d.next = false;
            self.tcs_n.d.next = false;
            self.dos.d.next = false;
            self.rbsa.d.next = 0.into();
            self.used.d.next = 0.into();
            self.rmc.d.next = 0.into();
            self.wr_busy.d.next = false;
            self.ram.write_enable.next = false;
        }

        // ------------------------------------------------------------------
        // Core.
        self.core.clock.next = self.clock.val();
        self.btr_reset.en.next = self.rst.val();
        self.core.reset.next = self.rst.val() | (!self.opm.q.val() & !self.boff.q.val());
        self.core.rx.next = self.rx.val();
        self.core.listen_only.next = self.lom.q.val();
        self.core.self_test.next = self.stm.q.val();
        self.core.single_shot.next = self.tx_single.q.val();
        self.core.host_recovery.next = true;
        self.core.recover.next = self.l_recover.val();
        self.core.tx_req.next = self.tx_pend.q.val() & !self.tx_lb.q.val() & self.opm.q.val();
        self.core.tx_ide.next = self.l_tx_ide.val();
        self.core.tx_rtr.next = self.l_tx_rtr.val();
        self.core.tx_id.next = self.l_tx_id.val();
        self.core.tx_dlc.next = self.txb0.q.val().get_bits::<4>(0);
        self.core.tx_data.next = self.l_tx_data.val();
        self.core.tx_abort.next = self.l_abort.val();
        self.core.cnt_load.next = self.l_cload.val() & !self.rst.val();
        self.core.tec_in.next = self.l_tecin.val();
        self.core.rec_in.next = self.l_recin.val();

        // ------------------------------------------------------------------
        // Outputs.
        self.tx.next = self.core.tx.val();
        self.wb_ack.next = self.ack.q.val();
        self.wb_dat_r.next = self.rdat.q.val();
        if self.ramsel.q.val() {
            self.wb_dat_r.next = self.ram.read_data.val();
        }
        self.int_n.next = !(self.l_irv.val().any());
    }
}

canstar_hdl::impl_clocked!(Sja1000);
