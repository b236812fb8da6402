//! Unit tests of the [`Engine`](super::engine::Engine) alone: characters go
//! straight into its queue port, a Rust Wishbone slave (a register array
//! with a settable SR, IR and receive window) records every access, and a
//! UART stand-in takes the transmitted characters.

use super::engine::Engine;
use super::SlcanParams;
use canstar_hdl::drive;
use std::collections::VecDeque;

struct Bench {
    e: Engine,
    regs: [u8; 128],
    writes: Vec<(u8, u8)>,
    reads: Vec<u8>,
    ack: Option<u8>,
    chars: VecDeque<u8>,
    out: Vec<u8>,
    uart: usize,
}

impl Bench {
    fn new(tx_wait: u32) -> Bench {
        let mut p = SlcanParams::with_clocks_per_bit(16_000_000, 8);
        p.tx_wait_polls = tx_wait;
        let mut e = Engine::new(&p);
        drive::init(&mut e);
        e.rst.next = true;
        drive::cycle(&mut e);
        e.rst.next = false;
        let mut regs = [0u8; 128];
        regs[2] = 0x0C; // SR: TBS, TCS
        Bench { e, regs, writes: vec![], reads: vec![], ack: None, chars: VecDeque::new(), out: vec![], uart: 0 }
    }

    fn step(&mut self) {
        let e = &mut self.e;
        e.c_valid.next = !self.chars.is_empty();
        e.c_data.next = (*self.chars.front().unwrap_or(&0) as u64).into();
        e.tx_busy.next = self.uart > 0;
        e.wb_ack.next = self.ack.is_some();
        e.wb_dat_r.next = (self.ack.unwrap_or(0) as u64).into();
        drive::settle(e);
        if e.c_pop.val() {
            self.chars.pop_front();
        }
        if e.tx_start.val() {
            assert_eq!(self.uart, 0, "a character started while the UART is busy");
            self.out.push(e.tx_data.val().index() as u8);
            self.uart = 5;
        } else {
            self.uart = self.uart.saturating_sub(1);
        }
        // Wishbone slave: acknowledge on the next clock, as the SJA1000 does
        let req = e.wb_cyc.val() && self.ack.is_none();
        let (we, a, d) = (e.wb_we.val(), e.wb_adr.val().index() as u8, e.wb_dat_w.val().index() as u8);
        drive::cycle(e);
        self.ack = None;
        if req {
            if we {
                self.writes.push((a, d));
                if a == 0x01 && d & 0x04 != 0 {
                    self.regs[2] &= !0x01; // RRB: the (one-frame) FIFO is empty
                }
                self.ack = Some(0);
            } else {
                self.reads.push(a);
                self.ack = Some(self.regs[a as usize & 0x7F]);
            }
        }
    }

    /// Send a line and run until the engine is idle again with the reply out.
    fn line(&mut self, l: &str) -> String {
        self.chars.extend(l.bytes());
        self.chars.push_back(b'\r');
        self.out.clear();
        for _ in 0..2000 {
            self.step();
        }
        String::from_utf8_lossy(&self.out).into_owned()
    }
}

#[test]
fn open_transmit_close() {
    let mut b = Bench::new(10);
    assert_eq!(b.line("s0000"), "\x07", "TSEG1 = 0");
    assert_eq!(b.line("s0014"), "\r", "8 TQ");
    assert_eq!(b.line("S6"), "\r");
    assert_eq!(b.line("O"), "\r");
    assert_eq!(b.writes, [(0x06, 0x00), (0x07, 0x1C), (0x04, 0xE8), (0x00, 0x00)]);
    b.writes.clear();
    assert_eq!(b.line("t1232aaBB"), "z\r");
    let mut want: Vec<(u8, u8)> = vec![(0x10, 0x02), (0x11, 0x24), (0x12, 0x60), (0x13, 0xAA), (0x14, 0xBB)];
    want.extend((0x15..0x1D).map(|a| (a, 0)));
    want.push((0x01, 0x01));
    assert_eq!(b.writes, want);
    b.writes.clear();
    // extended remote frame: FI = FF | RTR | DLC, ID << 3
    assert_eq!(b.line("R1ABCDEF05"), "Z\r");
    assert_eq!(&b.writes[..5], &[(0x10, 0xC5), (0x11, 0xD5), (0x12, 0xE6), (0x13, 0xF7), (0x14, 0x80)]);
    assert_eq!(b.writes.last(), Some(&(0x01, 0x01)));
    b.writes.clear();
    // TX buffer busy for longer than the wait: BEL, nothing written
    b.regs[2] = 0x00;
    b.reads.clear();
    assert_eq!(b.line("t0010"), "\x07");
    assert!(b.writes.is_empty());
    assert_eq!(b.reads.iter().filter(|&&a| a == 2).count() >= 11, true, "{:?}", b.reads);
    b.regs[2] = 0x0C;
    assert_eq!(b.line("C"), "\r");
    assert_eq!(b.writes, [(0x00, 0x01)]);
    // closed: no SR polling
    b.reads.clear();
    b.line("");
    assert!(b.reads.is_empty());
}

#[test]
fn received_frame_and_status_flags() {
    let mut b = Bench::new(10);
    assert_eq!(b.line("L"), "\r");
    assert_eq!(b.writes.last(), Some(&(0x00, 0x02)), "listen-only");
    // listen-only: transmission refused
    assert_eq!(b.line("t0010"), "\x07");
    b.writes.clear();
    // a standard frame in the window: ID 0x5A3, DLC 3
    b.regs[2] = 0x0D;
    b.regs[0x10..0x16].copy_from_slice(&[0x03, 0xB4, 0x60, 0x01, 0x02, 0x03]);
    b.out.clear();
    for _ in 0..2000 {
        b.step();
    }
    assert_eq!(String::from_utf8_lossy(&b.out), "t5A33010203\r");
    assert_eq!(b.writes, [(0x01, 0x04)], "RRB once");
    b.writes.clear();
    // F: SR = DOS | ES, TBS = 0; IR = BEI | ALI | DOI
    b.regs[2] = 0x42;
    b.regs[3] = 0xC8;
    assert_eq!(b.line("F"), "FCF\r");
    assert_eq!(b.writes, [(0x01, 0x08)], "CDO clears the overrun");
    b.regs[2] = 0x0C;
    b.regs[3] = 0x00;
    assert_eq!(b.line("F"), "F00\r");
    assert_eq!(b.line("V"), "V0101\r");
    assert_eq!(b.line("N"), "NCA57\r");
    assert_eq!(b.line("S7"), "\x07", "only when closed");
}
