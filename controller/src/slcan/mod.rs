//! slcan: the FPGA as a USB-to-CAN adapter speaking the Lawicel ASCII
//! protocol ("slcan") over the board's UART, in RTL around the
//! [`Sja1000`](crate::sja1000::Sja1000) top, so that Linux `slcand` +
//! SocketCAN and python-can's `slcan` interface drive it unchanged.
//!
//! # Structure (one concern per file)
//!
//! - [`uart`]: [`UartRx`](uart::UartRx) and [`UartTx`](uart::UartTx), 8N1,
//!   clocks per bit a generation-time constant;
//! - [`infifo`]: [`InFifo`](infifo::InFifo), the 63-byte queue of host
//!   characters between the UART receiver and the parser (one block RAM);
//! - [`parse`]: [`LineParser`](parse::LineParser), which turns host
//!   characters into the fields of one command line as they arrive;
//! - [`linetx`]: [`LineTx`](linetx::LineTx), the single transmit path: it
//!   sends one reply or frame line at a time (prefix, hex digits, CR);
//! - [`reply`]: [`Reply`](reply::Reply), the reply or frame line for a
//!   reply kind (combinational);
//! - [`engine`]: [`Engine`](engine::Engine), the command sequencer: it
//!   executes parsed lines and forwards received frames, driving the
//!   SJA1000 through its Wishbone port as a driver would;
//! - [`top`]: [`SlcanTop`](top::SlcanTop), UART + queue + parser + line
//!   transmitter + engine + `Sja1000`;
//! - this file: the generation-time parameters ([`SlcanParams`]): the
//!   UART divider and the `Sn` bit-rate table.
//!
//! # Protocol subset
//!
//! Host lines end with CR (0x0D); LF (0x0A) is ignored. OK is CR, an error
//! is BEL (0x07). `Sn` (n = 0..9, only when closed): 10k, 20k, 50k, 100k,
//! 125k, 250k, 500k, **800k (Lawicel's S7; python-can calls S7 750 kbit/s,
//! which this adapter does not provide)**, 1M, 83.3k (S9 as in python-can);
//! a rate the design clock cannot make exactly (within 0.1 %) answers BEL.
//! `sxxyy` sets BTR0/BTR1 (only when closed; BEL for TSEG1 = 0 or a bit
//! under 8 TQ, which the core refuses). `O` opens in normal mode, `L`
//! listen-only, `C` closes (reset mode; always OK). `t`/`T`/`r`/`R` transmit
//! (only when open in normal mode; `z\r` / `Z\r`). `F` answers `Fxx\r`
//! (Lawicel status flags, see [`engine`]), `V` answers `V0101\r`, `N`
//! answers `NCA57\r`, an empty line answers CR. Received frames are sent as
//! `tiiildd..\r`, `Tiiiiiiiildd..\r`, `riiil\r`, `Riiiiiiiil\r` (uppercase
//! hex; a received DLC above 8 is sent as 8).
//!
//! Not implemented (answer BEL): timestamps (`Z`), acceptance filter
//! commands (`M`, `m`: the block accepts every frame), `W`, `X`, `U`, `Q`,
//! `P`, `A`, CAN FD (`d`, `D`, `b`, `B`, `Y`).

pub mod engine;
pub mod infifo;
pub mod linetx;
pub mod parse;
pub mod reply;
pub mod top;
pub mod uart;

pub use top::SlcanTop;

use crate::sja1000::timing::core_timing;

/// The nominal design clock when none is given.
pub const DEFAULT_CLOCK_HZ: u64 = 16_000_000;
/// The UART baud rate when none is given.
pub const DEFAULT_BAUD: u64 = 115_200;
/// The largest relative error of the integer UART divider accepted.
pub const MAX_BAUD_ERROR: f64 = 0.02;

/// The `Sn` bit rates in bit/s (n = index); S9 is 83 1/3 kbit/s.
pub const SN_RATES: [f64; 10] = [
    10_000.0,
    20_000.0,
    50_000.0,
    100_000.0,
    125_000.0,
    250_000.0,
    500_000.0,
    800_000.0,
    1_000_000.0,
    250_000.0 / 3.0,
];

/// BTR0/BTR1 for `rate` at `clock_hz`, or `None` if no setting the core
/// honours makes the rate within 0.1 %. The smallest prescaler whose bit
/// has 8..=16 TQ is taken (else 17..=25 TQ), SJW = 1 TQ, TSEG2 = max(2,
/// round(TQ/8), TQ − 17) TQ, the rest TSEG1: at 16 MHz the classic Lawicel values
/// (500k = 0x00/0x1C, 800k = 0x00/0x16, 1M = 0x00/0x14, 10k = 0x31/0x1C).
pub fn btr_for(clock_hz: u64, rate: f64) -> Option<(u8, u8)> {
    for range in [8u32..=16, 17..=25] {
        for brp in 0u32..64 {
            let per_bit = clock_hz as f64 / (2.0 * (brp + 1) as f64 * rate);
            let ntq = per_bit.round();
            if !range.contains(&(ntq as u32)) || ((per_bit - ntq) / ntq).abs() > 1e-3 {
                continue;
            }
            let ntq = ntq as u32;
            // TSEG1 + 1 is at most 16 TQ, TSEG2 + 1 at most 8
            let t2 = ((ntq as f64 / 8.0).round() as u32).max(2).max(ntq.saturating_sub(17));
            let t1 = ntq - 1 - t2;
            if t1 > 16 || t2 > 8 {
                continue;
            }
            let (btr0, btr1) = (brp as u8, (((t2 - 1) << 4) | (t1 - 1)) as u8);
            if core_timing(btr0, btr1).is_ok() {
                return Some((btr0, btr1));
            }
        }
    }
    None
}

/// A 128-bit value as `Bits<128>`.
pub fn bits128(x: u128) -> rust_hdl::prelude::Bits<128> {
    use rust_hdl::prelude::*;
    let hi: Bits<64> = ((x >> 64) as u64).into();
    let lo: Bits<64> = (x as u64).into();
    (bit_cast::<128, 64>(hi) << 64) | bit_cast::<128, 64>(lo)
}

/// The generation-time parameters of [`SlcanTop`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SlcanParams {
    /// The nominal design clock (the `Sn` table is computed for it).
    pub clock_hz: u64,
    /// UART clocks per bit.
    pub clocks_per_bit: u32,
    /// BTR0/BTR1 of S0..S9 (`None`: the clock cannot make the rate).
    pub table: [Option<(u8, u8)>; 10],
    /// How many SR reads (4 clocks each) a transmit command waits for the
    /// TX buffer before answering BEL: 20 ms of the nominal clock.
    pub tx_wait_polls: u32,
}

impl SlcanParams {
    /// Parameters for a design clock and a UART baud rate: the integer
    /// divider must be within [`MAX_BAUD_ERROR`] of the baud rate.
    pub fn new(clock_hz: u64, baud: u64) -> Result<Self, String> {
        if baud == 0 || clock_hz == 0 {
            return Err(format!("clock {clock_hz} Hz, baud {baud}: both must be positive"));
        }
        let cpb = ((clock_hz as f64) / (baud as f64)).round() as u64;
        if cpb < 4 {
            return Err(format!(
                "baud {baud} at clock {clock_hz} Hz: {cpb} clocks per UART bit, the receiver needs at least 4"
            ));
        }
        if cpb > 0xFFFF {
            return Err(format!("baud {baud} at clock {clock_hz} Hz: {cpb} clocks per UART bit, at most 65535"));
        }
        let actual = clock_hz as f64 / cpb as f64;
        let err = (actual - baud as f64).abs() / baud as f64;
        if err >= MAX_BAUD_ERROR {
            return Err(format!(
                "baud {baud} at clock {clock_hz} Hz: the integer divider {cpb} gives {actual:.0} baud, {:.2} % off (at most {:.0} % allowed)",
                err * 100.0,
                MAX_BAUD_ERROR * 100.0
            ));
        }
        Ok(Self::with_clocks_per_bit(clock_hz, cpb as u32))
    }

    /// Parameters with an explicit UART divider (simulation: a small one
    /// keeps the host link fast).
    pub fn with_clocks_per_bit(clock_hz: u64, clocks_per_bit: u32) -> Self {
        assert!((4..=0xFFFF).contains(&clocks_per_bit), "clocks per UART bit must be 4..=65535");
        let mut table = [None; 10];
        for (k, r) in SN_RATES.iter().enumerate() {
            table[k] = btr_for(clock_hz, *r);
        }
        let tx_wait_polls = (clock_hz / 50 / 4).clamp(1, (1 << 20) - 1) as u32;
        Self { clock_hz, clocks_per_bit, table, tx_wait_polls }
    }

    /// The BTR0/BTR1 loaded at reset (before any `S`/`s`): S6 (500 kbit/s)
    /// if the clock makes it, else the first rate it makes, else 0/0.
    pub fn default_btr(&self) -> (u8, u8) {
        self.table[6].or_else(|| self.table.iter().flatten().next().copied()).unwrap_or((0, 0))
    }
}

impl Default for SlcanParams {
    fn default() -> Self {
        Self::new(DEFAULT_CLOCK_HZ, DEFAULT_BAUD).unwrap()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lawicel_values_at_16_mhz() {
        let p = SlcanParams::new(16_000_000, 115_200).unwrap();
        let want = [(0x31, 0x1C), (0x18, 0x1C), (0x09, 0x1C), (0x04, 0x1C), (0x03, 0x1C), (0x01, 0x1C), (0x00, 0x1C), (0x00, 0x16), (0x00, 0x14)];
        for (k, w) in want.iter().enumerate() {
            assert_eq!(p.table[k], Some(*w), "S{k}");
        }
        // 83.3k: 16 MHz / (2 * 6 * 16)
        assert_eq!(p.table[9], Some((0x05, 0x1C)));
        assert_eq!(p.clocks_per_bit, 139);
        assert_eq!(p.default_btr(), (0x00, 0x1C));
    }

    #[test]
    fn every_entry_is_exact_for_the_core() {
        for clk in [8_000_000u64, 16_000_000, 24_000_000, 14_740_000, 48_000_000] {
            let p = SlcanParams::with_clocks_per_bit(clk, 16);
            for (k, e) in p.table.iter().enumerate() {
                if let Some((b0, b1)) = e {
                    let t = core_timing(*b0, *b1).unwrap();
                    let rate = clk as f64 / (t.brp as f64 * t.ntq() as f64);
                    assert!((rate / SN_RATES[k] - 1.0).abs() < 1e-3, "{clk} S{k}: {rate}");
                }
            }
        }
        // 14.74 MHz cannot make 1 Mbit/s exactly
        assert_eq!(SlcanParams::with_clocks_per_bit(14_740_000, 16).table[8], None);
    }

    #[test]
    fn baud_divider_error_is_checked() {
        assert!(SlcanParams::new(16_000_000, 115_200).is_ok());
        let e = SlcanParams::new(1_000_000, 115_200).unwrap_err();
        assert!(e.contains("% off"), "{e}");
        assert!(SlcanParams::new(16_000_000, 8_000_000).unwrap_err().contains("at least 4"));
    }
}
#[cfg(test)]
mod engine_tests;
