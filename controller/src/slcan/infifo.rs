//! [`InFifo`]: the queue of host characters between the UART receiver and
//! the line parser: 63 entries of 9 bits in one block RAM (bit 8 marks a
//! character before which characters were lost), so that the host may send
//! while the engine is busy (executing a command, or waiting for the line
//! transmitter while a received frame goes out).
//!
//! State: `wp`, `rp` (RAM write and read addresses), `cnt` (entries written
//! and not yet fetched, 0..=63), `fetch` (a RAM read is in flight: the RAM
//! reads on the clock edge), `ov`, `od` (the output register and its valid
//! flag), `lost` (a character was dropped: the queue was full or the UART
//! reported a framing error; the next stored character gets bit 8).
//! A character is fetched only when it was written on an earlier clock edge,
//! so a read never meets a write of the same address. Output latency 2
//! clocks, one character every 2 clocks: far faster than the UART.
//! `rst` empties the queue.

use rust_hdl::prelude::*;

#[derive(LogicBlock)]
pub struct InFifo {
    pub clock: Signal<In, Clock>,
    pub rst: Signal<In, Bit>,
    /// A character from the UART (one clock).
    pub push: Signal<In, Bit>,
    pub wdata: Signal<In, Bits<8>>,
    /// A character was lost on the line (framing error).
    pub lose: Signal<In, Bit>,
    /// Take the output character (only when `valid`).
    pub pop: Signal<In, Bit>,
    pub valid: Signal<Out, Bit>,
    /// Bit 8: characters were lost before this one.
    pub rdata: Signal<Out, Bits<9>>,

    ram: RAM<Bits<9>, 6>,
    wp: DFF<Bits<6>>,
    rp: DFF<Bits<6>>,
    cnt: DFF<Bits<6>>,
    fetch: DFF<Bit>,
    ov: DFF<Bit>,
    od: DFF<Bits<9>>,
    lost: DFF<Bit>,
    l_wr: Signal<Local, Bit>,
    l_rd: Signal<Local, Bit>,
    l_wd: Signal<Local, Bits<9>>,
}

impl Default for InFifo {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            rst: Default::default(),
            push: Default::default(),
            wdata: Default::default(),
            lose: Default::default(),
            pop: Default::default(),
            valid: Default::default(),
            rdata: Default::default(),
            ram: Default::default(),
            wp: Default::default(),
            rp: Default::default(),
            cnt: Default::default(),
            fetch: Default::default(),
            ov: Default::default(),
            od: Default::default(),
            lost: Default::default(),
            l_wr: Default::default(),
            l_rd: Default::default(),
            l_wd: Default::default(),
        }
    }
}

impl Logic for InFifo {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, wp, rp, cnt, fetch, ov, od, lost);
        self.ram.read_clock.next = self.clock.val();
        self.ram.write_clock.next = self.clock.val();

        self.l_wr.next = self.push.val() & (self.cnt.q.val() != 63);
        self.l_rd.next = (self.cnt.q.val() != 0) & !self.fetch.q.val() & (!self.ov.q.val() | self.pop.val());
        self.ram.write_address.next = self.wp.q.val();
        self.l_wd.next = bit_cast::<9, 8>(self.wdata.val());
        if self.lost.q.val() {
            self.l_wd.next = bit_cast::<9, 8>(self.wdata.val()) | 0x100;
        }
        self.ram.write_data.next = self.l_wd.val();
        self.ram.write_enable.next = self.l_wr.val();
        self.ram.read_address.next = self.rp.q.val();

        if self.l_wr.val() {
            self.wp.d.next = self.wp.q.val() + 1;
            self.lost.d.next = false;
        }
        if (self.push.val() & !self.l_wr.val()) | self.lose.val() {
            self.lost.d.next = true;
        }
        if self.l_rd.val() {
            self.rp.d.next = self.rp.q.val() + 1;
        }
        if self.l_wr.val() & !self.l_rd.val() {
            self.cnt.d.next = self.cnt.q.val() + 1;
        }
        if !self.l_wr.val() & self.l_rd.val() {
            self.cnt.d.next = self.cnt.q.val() - 1;
        }
        self.fetch.d.next = self.l_rd.val();
        if self.pop.val() {
            self.ov.d.next = false;
        }
        if self.fetch.q.val() {
            self.ov.d.next = true;
            self.od.d.next = self.ram.read_data.val();
        }
        if self.rst.val() {
            self.wp.d.next = 0.into();
            self.rp.d.next = 0.into();
            self.cnt.d.next = 0.into();
            self.fetch.d.next = false;
            self.ov.d.next = false;
            self.od.d.next = 0.into();
            self.lost.d.next = false;
        }
        self.valid.next = self.ov.q.val();
        self.rdata.next = self.od.q.val();
    }
}

canstar_hdl::impl_clocked!(InFifo);

#[cfg(test)]
mod tests {
    use super::*;
    use canstar_hdl::drive;

    fn step(f: &mut InFifo, push: Option<u64>, lose: bool, pop: bool, got: &mut Vec<u64>) {
        f.push.next = push.is_some();
        f.wdata.next = push.unwrap_or(0).into();
        f.lose.next = lose;
        f.pop.next = pop && f.valid.val();
        if pop && f.valid.val() {
            got.push(f.rdata.val().index() as u64);
        }
        drive::cycle(f);
    }

    #[test]
    fn order_overflow_mark_and_framing_error() {
        let mut f = InFifo::default();
        drive::init(&mut f);
        f.rst.next = true;
        drive::cycle(&mut f);
        f.rst.next = false;
        let mut got = vec![];
        // 70 characters with nobody reading: 63 in the RAM + 1 in the
        // output register, the rest lost
        for k in 0..70u64 {
            step(&mut f, Some(k), false, false, &mut got);
        }
        for _ in 0..5 {
            step(&mut f, None, false, true, &mut got);
        }
        step(&mut f, Some(100), false, true, &mut got);
        step(&mut f, Some(101), false, true, &mut got);
        step(&mut f, None, true, true, &mut got);
        step(&mut f, Some(102), false, true, &mut got);
        for _ in 0..300 {
            step(&mut f, None, false, true, &mut got);
        }
        let mut want: Vec<u64> = (0..64).collect();
        want.extend([0x100 | 100, 101, 0x100 | 102]);
        assert_eq!(got, want);
    }
}
