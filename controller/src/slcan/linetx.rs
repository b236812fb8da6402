//! [`LineTx`]: the single transmit path to the host. It sends one line at a
//! time: an optional prefix character, `cnt` hex digits (uppercase, taken
//! from the top of `nib`, first digit in bits 127..124) and an optional CR,
//! one character whenever the UART transmitter is free. A new line is
//! loaded only while `busy` = 0, so replies to host commands and received
//! frames can never interleave inside a line.
//!
//! State: `ph` (0 idle, 1 prefix, 2 digits, 3 CR), `pre`, `haspre`, `nb`
//! (digits still to send, shifted left as they go), `cnt`, `cr`. `rst`
//! returns to idle.

use rust_hdl::prelude::*;

#[derive(LogicBlock)]
pub struct LineTx {
    pub clock: Signal<In, Clock>,
    pub rst: Signal<In, Bit>,
    pub load: Signal<In, Bit>,
    pub l_pre: Signal<In, Bits<8>>,
    pub l_haspre: Signal<In, Bit>,
    pub l_nib: Signal<In, Bits<128>>,
    pub l_cnt: Signal<In, Bits<5>>,
    pub l_cr: Signal<In, Bit>,
    pub busy: Signal<Out, Bit>,
    /// The UART transmitter.
    pub tx_busy: Signal<In, Bit>,
    pub tx_start: Signal<Out, Bit>,
    pub tx_data: Signal<Out, Bits<8>>,

    ph: DFF<Bits<2>>,
    pre: DFF<Bits<8>>,
    haspre: DFF<Bit>,
    nb: DFF<Bits<128>>,
    cnt: DFF<Bits<5>>,
    cr: DFF<Bit>,
    l_d: Signal<Local, Bits<4>>,
    l_ts: Signal<Local, Bit>,
    l_td: Signal<Local, Bits<8>>,
}

impl Default for LineTx {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            rst: Default::default(),
            load: Default::default(),
            l_pre: Default::default(),
            l_haspre: Default::default(),
            l_nib: Default::default(),
            l_cnt: Default::default(),
            l_cr: Default::default(),
            busy: Default::default(),
            tx_busy: Default::default(),
            tx_start: Default::default(),
            tx_data: Default::default(),
            ph: Default::default(),
            pre: Default::default(),
            haspre: Default::default(),
            nb: Default::default(),
            cnt: Default::default(),
            cr: Default::default(),
            l_d: Default::default(),
            l_ts: Default::default(),
            l_td: Default::default(),
        }
    }
}

impl Logic for LineTx {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, ph, pre, haspre, nb, cnt, cr);
        self.l_ts.next = false;
        self.l_d.next = self.nb.q.val().get_bits::<4>(124);
        self.l_td.next = self.pre.q.val();
        if self.ph.q.val() == 2 {
            self.l_td.next = bit_cast::<8, 4>(self.l_d.val()) + 0x30;
            if self.l_d.val() > 9 {
                self.l_td.next = bit_cast::<8, 4>(self.l_d.val()) + 0x37;
            }
        }
        if self.ph.q.val() == 3 {
            self.l_td.next = 0x0D.into();
        }
        if self.ph.q.val() == 0 {
            if self.load.val() {
                self.ph.d.next = 1.into();
                self.pre.d.next = self.l_pre.val();
                self.haspre.d.next = self.l_haspre.val();
                self.nb.d.next = self.l_nib.val();
                self.cnt.d.next = self.l_cnt.val();
                self.cr.d.next = self.l_cr.val();
            }
        }
        if self.ph.q.val() == 1 {
            if !self.haspre.q.val() {
                self.ph.d.next = 2.into();
            } else if !self.tx_busy.val() {
                self.l_ts.next = true;
                self.ph.d.next = 2.into();
            }
        }
        if self.ph.q.val() == 2 {
            if self.cnt.q.val() == 0 {
                self.ph.d.next = 3.into();
            } else if !self.tx_busy.val() {
                self.l_ts.next = true;
                self.nb.d.next = self.nb.q.val() << 4;
                self.cnt.d.next = self.cnt.q.val() - 1;
            }
        }
        if self.ph.q.val() == 3 {
            if !self.cr.q.val() {
                self.ph.d.next = 0.into();
            } else if !self.tx_busy.val() {
                self.l_ts.next = true;
                self.ph.d.next = 0.into();
            }
        }
        if self.rst.val() {
            self.ph.d.next = 0.into();
            self.cnt.d.next = 0.into();
            self.haspre.d.next = false;
            self.cr.d.next = false;
        }
        // outputs assigned once (no glitch reaches another block)
        self.busy.next = self.ph.q.val() != 0;
        self.tx_start.next = self.l_ts.val();
        self.tx_data.next = self.l_td.val();
    }
}

canstar_hdl::impl_clocked!(LineTx);

#[cfg(test)]
mod tests {
    use super::*;
    use canstar_hdl::drive;

    #[test]
    fn lines_go_out_whole() {
        let mut t = LineTx::default();
        drive::init(&mut t);
        t.rst.next = true;
        drive::cycle(&mut t);
        t.rst.next = false;
        // (prefix, digits, cr)
        let lines: [(Option<u8>, &str, bool); 4] =
            [(Some(b't'), "1238DEADBEEF01234567", true), (None, "", true), (Some(7), "", false), (Some(b'F'), "A5", true)];
        let mut out = vec![];
        let mut uart_busy = 0;
        for (pre, digits, cr) in lines {
            while t.busy.val() {
                t.load.next = false;
                t.tx_busy.next = uart_busy > 0;
                drive::settle(&mut t);
                if t.tx_start.val() {
                    assert_eq!(uart_busy, 0);
                    out.push(t.tx_data.val().index() as u8);
                    uart_busy = 3;
                } else if uart_busy > 0 {
                    uart_busy -= 1;
                }
                drive::cycle(&mut t);
            }
            let mut nib = 0u128;
            for (k, c) in digits.chars().enumerate() {
                nib |= (c.to_digit(16).unwrap() as u128) << (124 - 4 * k);
            }
            t.load.next = true;
            t.l_pre.next = (pre.unwrap_or(0) as u64).into();
            t.l_haspre.next = pre.is_some();
            t.l_nib.next = super::super::bits128(nib);
            t.l_cnt.next = (digits.len() as u64).into();
            t.l_cr.next = cr;
            drive::cycle(&mut t);
            assert!(t.busy.val());
        }
        t.load.next = false;
        for _ in 0..200 {
            t.tx_busy.next = uart_busy > 0;
            drive::settle(&mut t);
            if t.tx_start.val() {
                out.push(t.tx_data.val().index() as u8);
                uart_busy = 3;
            } else if uart_busy > 0 {
                uart_busy -= 1;
            }
            drive::cycle(&mut t);
        }
        assert_eq!(out, b"t1238DEADBEEF01234567\r\r\x07FA5\r");
    }
}
