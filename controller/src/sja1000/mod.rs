//! [`Sja1000`]: an NXP SJA1000 (PeliCAN mode) compatible register block on a
//! Wishbone B4 classic slave, wrapping [`CanCore`](crate::core::CanCore), with the 64-byte receive
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
//! # Register map
//!
//! The PeliCAN map; the table with addresses, access per mode, reset values
//! and bit names is [`regs`] (the RTL and the tests both read it). In short:
//! 0x00 MOD, 0x01 CMR (write only), 0x02 SR, 0x03 IR, 0x04 IER, 0x06/0x07
//! BTR0/BTR1, 0x08 OCR, 0x0B ALC, 0x0C ECC, 0x0D EWL, 0x0E/0x0F
//! RXERR/TXERR, 0x10..0x1C (operating mode: read = receive window, write =
//! transmit buffer; reset mode: ACR0..3, AMR0..3 at 0x10..0x17), 0x1D RMC,
//! 0x1E RBSA, 0x1F CDR, 0x20..0x5F the FIFO RAM, 0x60..0x6C the transmit
//! buffer; other addresses read 0x00 and ignore writes.
//!
//! # Structure
//!
//! - [`regs`]: the register table and the `REG_*`, `MOD_*`, `CMD_*`,
//!   `SR_*`, `IRQ_*`, `ECC_*` constants;
//! - [`top`]: [`Sja1000`]: the Wishbone slave, address decoding and read
//!   multiplexer, OCR/EWL/CDR, and the composition of the core with:
//! - [`mode`]: MOD (reset mode, listen-only, self test, filter mode, sleep);
//! - [`txctl`]: the transmit commands and TBS/TCS/TI;
//! - [`status`]: SR, the error counters as seen by the host, ES/BS/EPI,
//!   the bus-off hold and the reset-mode counter load;
//! - [`irq`]: IER, IR and the INT output;
//! - [`timing`]: BTR0/BTR1 and their mapping onto the core's bit timing;
//! - [`txbuf`]: the transmit buffer;
//! - [`filter`]: the acceptance code/mask registers and filters;
//! - [`fifo`]: the receive FIFO: candidate frame, RAM, writer and release;
//! - [`capture`]: the ALC and ECC capture registers.
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
//! - **Bit timing**: BTR0/BTR1 are mapped exactly onto the core's fields
//!   ([`timing`]). Every BRP 0..63: TQ = 2·(BRP+1) clocks (the core's
//!   prescaler field is 2·BRP+1, 7 bits). With t1 = TSEG1+1 (1..16 TQ) and
//!   t2 = TSEG2+1 (1..8 TQ): PH1 = min(t1 − 1, 8), PROP = t1 − PH1, PH2 =
//!   t2, so the bit is 1 + t1 + t2 TQ with the sample point after 1 + t1 TQ,
//!   as on the SJA1000, TSEG2 = 0 (PH2 = 1 TQ) included: a TQ is at least 2
//!   clocks, the information processing time the core needs
//!   (can-protocol.md §2.5, C1). SJW may exceed PH2 but is limited to PH1
//!   (C22), which changes it only when t1 ≤ SJW. The core refuses bit times
//!   below 8 TQ and TSEG1 = 0 (a sample point 2 TQ after the bit start: PROP
//!   and PH1 are at least 1 TQ each); it then stays inert (TX recessive,
//!   RS = TS = 1). [`timing::core_timing`] names these settings, and the
//!   SJW-limited ones, for Rust callers. SAM selects triple sampling.
//! - **TS/RS** are both 1 while the core waits for bus idle (reset, the
//!   11-bit integration, bus-off), as the SJA1000's 0x3C status after reset;
//!   otherwise TS = transmitting, RS = receiving a frame (SOF to the end of
//!   error/overload frames).
//! - **Commands**: TR and SRR are taken in operating mode when TBS = 1 and
//!   the node is not sleeping (else ignored); with AT in the same write the
//!   transmission is single shot. AT alone while a transmission is pending
//!   aborts it: if it has not started TBS = 1 at once, else at the end of
//!   the frame. TCS goes to 0 with the TR/SRR request and to 1 only when a
//!   transmission succeeds, so after an abort or bus-off it reads 0. TI is
//!   raised whenever TBS goes back to 1 (success, single-shot failure,
//!   abort). Writes to the TX
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

pub mod capture;
pub mod status;
pub mod fifo;
pub mod filter;
pub mod irq;
pub mod mode;
pub mod regs;
pub mod timing;
pub mod top;
pub mod txctl;
pub mod txbuf;

pub use regs::{
    CDR_PELICAN, CMD_AT, CMD_CDO, CMD_RRB, CMD_SRR, CMD_TR, ECC_BIT, ECC_DIR, ECC_FORM, ECC_MASK, ECC_OTHER, ECC_SEG,
    ECC_STUFF, FI_FF, FI_RTR, IRQ_ALI, IRQ_BEI, IRQ_DOI, IRQ_EI, IRQ_EPI, IRQ_RI, IRQ_TI, IRQ_WUI, MOD_AFM, MOD_LOM,
    MOD_RM, MOD_SM, MOD_STM, REG_ACCC0, REG_ACCM0, REG_ALC, REG_BTR0, REG_BTR1, REG_CDR, REG_CMR, REG_ECC, REG_EWL,
    REG_FI, REG_ID1, REG_IER, REG_IR, REG_MOD, REG_OCR, REG_RBSA, REG_RMC, REG_RXERR, REG_RXFIFO, REG_SR, REG_TXBUF,
    REG_TXERR, SR_BS, SR_DOS, SR_ES, SR_RBS, SR_RS, SR_TBS, SR_TCS, SR_TS,
};
pub use top::Sja1000;
