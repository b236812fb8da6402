//! UART 8N1 receiver [`UartRx`] and transmitter [`UartTx`]; the number of
//! clocks per bit (`cpb`, at least 4) is a generation-time constant.
//!
//! [`UartRx`] state: `s1`, `s2` (2-flip-flop synchroniser of `rxd`, reset
//! to 1 = idle); `st` (Idle, Start, Data, Stop, Break); `cnt` (clocks in the
//! bit); `nbit` (data bits taken); `sh` (the shift register, LSB first).
//! A falling edge starts a character; the start bit is checked again
//! mid-bit (a low pulse shorter than half a bit is a glitch: back to idle,
//! nothing reported); data bits are sampled mid-bit, every `cpb` clocks;
//! the stop bit is sampled mid-bit: 1 gives `valid` with `data` for one
//! clock, 0 gives `ferr` for one clock and the receiver waits for the line
//! to return high (a break gives one framing error, not a stream of 0x00).
//! No oversampling vote, no parity, no FIFO (see [`super::infifo`]).
//!
//! [`UartTx`] state: `busy`, `sh` (start, 8 data, stop, LSB first), `cnt`,
//! `nbit`. `start` while `busy` = 0 takes `data`; `busy` is 1 from the next
//! clock until the end of the stop bit. `txd` is registered (1 when idle).
//! `rst` returns both to idle.

use rust_hdl::prelude::*;

#[derive(Copy, Clone, Debug, PartialEq, Eq, LogicState)]
pub enum RxState {
    Idle,
    Start,
    Data,
    Stop,
    Break,
}

#[derive(LogicBlock)]
pub struct UartRx {
    pub clock: Signal<In, Clock>,
    pub rst: Signal<In, Bit>,
    pub rxd: Signal<In, Bit>,
    pub data: Signal<Out, Bits<8>>,
    pub valid: Signal<Out, Bit>,
    pub ferr: Signal<Out, Bit>,

    s1: DFF<Bit>,
    s2: DFF<Bit>,
    st: DFF<RxState>,
    cnt: DFF<Bits<16>>,
    nbit: DFF<Bits<4>>,
    sh: DFF<Bits<8>>,
    vld: DFF<Bit>,
    fe: DFF<Bit>,
    /// cpb − 1 and cpb/2 − 1.
    last: Constant<Bits<16>>,
    half: Constant<Bits<16>>,
}

impl UartRx {
    pub fn new(cpb: u32) -> Self {
        assert!((4..=0xFFFF).contains(&cpb));
        Self {
            clock: Default::default(),
            rst: Default::default(),
            rxd: Default::default(),
            data: Default::default(),
            valid: Default::default(),
            ferr: Default::default(),
            s1: Default::default(),
            s2: Default::default(),
            st: Default::default(),
            cnt: Default::default(),
            nbit: Default::default(),
            sh: Default::default(),
            vld: Default::default(),
            fe: Default::default(),
            last: Constant::new(((cpb - 1) as u64).into()),
            half: Constant::new(((cpb / 2 - 1) as u64).into()),
        }
    }
}

impl Logic for UartRx {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, s1, s2, st, cnt, nbit, sh, vld, fe);
        self.s1.d.next = self.rxd.val();
        self.s2.d.next = self.s1.q.val();
        self.vld.d.next = false;
        self.fe.d.next = false;
        self.cnt.d.next = self.cnt.q.val() + 1;
        match self.st.q.val() {
            RxState::Idle => {
                self.cnt.d.next = 0.into();
                if !self.s2.q.val() {
                    self.st.d.next = RxState::Start;
                }
            }
            RxState::Start => {
                if self.cnt.q.val() == self.half.val() {
                    self.cnt.d.next = 0.into();
                    self.nbit.d.next = 0.into();
                    if self.s2.q.val() {
                        // a glitch, not a start bit
                        self.st.d.next = RxState::Idle;
                    } else {
                        self.st.d.next = RxState::Data;
                    }
                }
            }
            RxState::Data => {
                if self.cnt.q.val() == self.last.val() {
                    self.cnt.d.next = 0.into();
                    self.sh.d.next = (self.sh.q.val() >> 1) | (bit_cast::<8, 1>(self.s2.q.val().into()) << 7);
                    self.nbit.d.next = self.nbit.q.val() + 1;
                    if self.nbit.q.val() == 7 {
                        self.st.d.next = RxState::Stop;
                    }
                }
            }
            RxState::Stop => {
                if self.cnt.q.val() == self.last.val() {
                    if self.s2.q.val() {
                        self.vld.d.next = true;
                        self.st.d.next = RxState::Idle;
                    } else {
                        self.fe.d.next = true;
                        self.st.d.next = RxState::Break;
                    }
                }
            }
            RxState::Break => {
                if self.s2.q.val() {
                    self.st.d.next = RxState::Idle;
                }
            }
        }
        if self.rst.val() {
            self.s1.d.next = true;
            self.s2.d.next = true;
            self.st.d.next = RxState::Idle;
            self.vld.d.next = false;
            self.fe.d.next = false;
            self.cnt.d.next = 0.into();
            self.nbit.d.next = 0.into();
            self.sh.d.next = 0.into();
        }
        self.data.next = self.sh.q.val();
        self.valid.next = self.vld.q.val();
        self.ferr.next = self.fe.q.val();
    }
}

canstar_hdl::impl_clocked!(UartRx);

#[derive(LogicBlock)]
pub struct UartTx {
    pub clock: Signal<In, Clock>,
    pub rst: Signal<In, Bit>,
    pub start: Signal<In, Bit>,
    pub data: Signal<In, Bits<8>>,
    pub busy: Signal<Out, Bit>,
    pub txd: Signal<Out, Bit>,

    bsy: DFF<Bit>,
    sh: DFF<Bits<10>>,
    cnt: DFF<Bits<16>>,
    nbit: DFF<Bits<4>>,
    last: Constant<Bits<16>>,
}

impl UartTx {
    pub fn new(cpb: u32) -> Self {
        assert!((4..=0xFFFF).contains(&cpb));
        Self {
            clock: Default::default(),
            rst: Default::default(),
            start: Default::default(),
            data: Default::default(),
            busy: Default::default(),
            txd: Default::default(),
            bsy: Default::default(),
            sh: Default::default(),
            cnt: Default::default(),
            nbit: Default::default(),
            last: Constant::new(((cpb - 1) as u64).into()),
        }
    }
}

impl Logic for UartTx {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, bsy, sh, cnt, nbit);
        if self.bsy.q.val() {
            self.cnt.d.next = self.cnt.q.val() + 1;
            if self.cnt.q.val() == self.last.val() {
                self.cnt.d.next = 0.into();
                self.sh.d.next = (self.sh.q.val() >> 1) | 0x200;
                self.nbit.d.next = self.nbit.q.val() + 1;
                if self.nbit.q.val() == 9 {
                    self.bsy.d.next = false;
                }
            }
        } else if self.start.val() {
            self.bsy.d.next = true;
            self.cnt.d.next = 0.into();
            self.nbit.d.next = 0.into();
            // stop bit, data (LSB first), start bit
            self.sh.d.next = (bit_cast::<10, 8>(self.data.val()) << 1) | 0x200;
        }
        if self.rst.val() {
            self.bsy.d.next = false;
            self.sh.d.next = 0x3FF.into();
            self.cnt.d.next = 0.into();
            self.nbit.d.next = 0.into();
        }
        self.busy.next = self.bsy.q.val();
        self.txd.next = self.sh.q.val().get_bit(0) | !self.bsy.q.val();
    }
}

canstar_hdl::impl_clocked!(UartTx);

#[cfg(test)]
mod tests {
    use super::*;
    use canstar_hdl::drive;

    fn rx(cpb: u32) -> UartRx {
        let mut u = UartRx::new(cpb);
        drive::init(&mut u);
        u.rxd.next = true;
        u.rst.next = true;
        drive::cycle(&mut u);
        u.rst.next = false;
        drive::cycle(&mut u);
        u
    }

    /// Feed line levels (one per clock); the received bytes and framing errors.
    fn feed(u: &mut UartRx, levels: &[bool]) -> (Vec<u8>, usize) {
        let (mut got, mut fe) = (vec![], 0);
        for &l in levels {
            u.rxd.next = l;
            drive::cycle(u);
            if u.valid.val() {
                got.push(u.data.val().index() as u8);
            }
            if u.ferr.val() {
                fe += 1;
            }
        }
        (got, fe)
    }

    fn frame(b: u8, cpb: usize, stop: bool) -> Vec<bool> {
        let mut v = vec![false; cpb];
        for k in 0..8 {
            v.extend(std::iter::repeat(b >> k & 1 == 1).take(cpb));
        }
        v.extend(std::iter::repeat(stop).take(cpb));
        v
    }

    #[test]
    fn receives_bytes_back_to_back() {
        let mut u = rx(8);
        let mut lv = vec![true; 20];
        for b in [0x55u8, 0x00, 0xFF, 0x0D, 0xA7] {
            lv.extend(frame(b, 8, true));
        }
        lv.extend(vec![true; 20]);
        assert_eq!(feed(&mut u, &lv), (vec![0x55, 0x00, 0xFF, 0x0D, 0xA7], 0));
    }

    #[test]
    fn tolerates_baud_mismatch() {
        // the sender is 4 % slow: 25 clocks per bit against 24
        let mut u = rx(24);
        let mut lv = vec![true; 30];
        lv.extend(frame(0x96, 25, true));
        lv.extend(vec![true; 30]);
        assert_eq!(feed(&mut u, &lv), (vec![0x96], 0));
    }

    #[test]
    fn start_glitch_is_rejected_and_framing_error_flagged() {
        let mut u = rx(16);
        let mut lv = vec![true; 20];
        // a 5-clock low pulse: not a start bit
        lv.extend(vec![false; 5]);
        lv.extend(vec![true; 40]);
        assert_eq!(feed(&mut u, &lv.clone()), (vec![], 0));
        // a character with a low stop bit, the line then held low (break)
        let mut lv = frame(0x41, 16, false);
        lv.extend(vec![false; 200]);
        lv.extend(vec![true; 20]);
        lv.extend(frame(0x42, 16, true));
        lv.extend(vec![true; 20]);
        assert_eq!(feed(&mut u, &lv), (vec![0x42], 1));
    }

    #[test]
    fn transmitter_to_receiver() {
        let cpb = 6;
        let mut t = UartTx::new(cpb);
        drive::init(&mut t);
        t.rst.next = true;
        drive::cycle(&mut t);
        t.rst.next = false;
        let mut r = rx(cpb);
        let bytes = [0x00u8, 0x5A, 0xFF, 0x0D, 0x07, 0x81];
        let (mut k, mut got) = (0, vec![]);
        let mut busy_clocks = 0;
        for _ in 0..(bytes.len() * 10 * cpb as usize + 50) {
            t.start.next = k < bytes.len() && !t.busy.val();
            if k < bytes.len() {
                t.data.next = (bytes[k] as u64).into();
            }
            let took = k < bytes.len() && !t.busy.val();
            drive::settle(&mut t);
            r.rxd.next = t.txd.val();
            drive::cycle(&mut t);
            drive::cycle(&mut r);
            if took {
                k += 1;
            }
            if t.busy.val() {
                busy_clocks += 1;
            }
            if r.valid.val() {
                got.push(r.data.val().index() as u8);
            }
            assert!(!r.ferr.val());
        }
        assert_eq!(got, bytes);
        // back to back: 10 bits per byte, no idle bit in between
        assert_eq!(busy_clocks, bytes.len() * 10 * cpb as usize);
    }
}
