//! Test layer for the slcan top: [`SlcanSim`], the `SlcanTop` with a host
//! UART model (a transmitter that sends queued bytes back to back as soon
//! as its line is free, and a receiver sampling mid-bit), as a [`Peer`] on
//! the SJA1000 harness's wired-AND bus.
#![allow(dead_code)]

use super::sja1000_util::{CtrlMode, Net, Peer};
use canstar_controller::frame::Frame;
use canstar_controller::slcan::{SlcanParams, SlcanTop};
use canstar_hdl::drive;
use std::cell::RefCell;
use std::collections::VecDeque;
use std::rc::Rc;

pub struct SlcanSim {
    pub top: Box<SlcanTop>,
    pub cpb: usize,
    /// Bytes the host still has to send.
    pub to_send: VecDeque<u8>,
    /// Line levels of the byte being sent (one per clock).
    tx_levels: VecDeque<bool>,
    /// Host receiver: clocks since the start edge (None: idle), the bits.
    rx_at: Option<usize>,
    rx_bits: u16,
    last: bool,
    /// Bytes the host received.
    pub received: Vec<u8>,
    /// Framing errors the host receiver saw.
    pub host_ferr: usize,
    pub cycles: u64,
    /// The level the top's CAN receiver sees instead of the bus (None: the bus).
    pub rx_force: Option<bool>,
}

impl SlcanSim {
    pub fn new(p: &SlcanParams) -> SlcanSim {
        let mut top = Box::new(SlcanTop::new(p));
        drive::init(&mut *top);
        top.rx.next = true;
        top.uart_rx.next = true;
        top.rst.next = true;
        drive::cycle(&mut *top);
        drive::cycle(&mut *top);
        top.rst.next = false;
        drive::cycle(&mut *top);
        SlcanSim {
            top,
            cpb: p.clocks_per_bit as usize,
            to_send: VecDeque::new(),
            tx_levels: VecDeque::new(),
            rx_at: None,
            rx_bits: 0,
            last: true,
            received: vec![],
            host_ferr: 0,
            cycles: 0,
            rx_force: None,
        }
    }

    /// The host line is idle and nothing is queued.
    pub fn host_idle(&self) -> bool {
        self.to_send.is_empty() && self.tx_levels.is_empty()
    }

    pub fn send(&mut self, bytes: &[u8]) {
        self.to_send.extend(bytes.iter().copied());
    }

    pub fn step_bus(&mut self, bus: bool) {
        if self.tx_levels.is_empty() {
            if let Some(b) = self.to_send.pop_front() {
                self.tx_levels.extend(std::iter::repeat(false).take(self.cpb));
                for k in 0..8 {
                    self.tx_levels.extend(std::iter::repeat(b >> k & 1 == 1).take(self.cpb));
                }
                self.tx_levels.extend(std::iter::repeat(true).take(self.cpb));
            }
        }
        self.top.uart_rx.next = self.tx_levels.pop_front().unwrap_or(true);
        self.top.rx.next = self.rx_force.unwrap_or(bus);
        drive::cycle(&mut *self.top);
        self.cycles += 1;
        // host receiver, sampling mid-bit
        let l = self.top.uart_tx.val();
        match self.rx_at {
            None => {
                if self.last && !l {
                    self.rx_at = Some(0);
                    self.rx_bits = 0;
                }
            }
            Some(t) => {
                let t = t + 1;
                self.rx_at = Some(t);
                let half = self.cpb / 2;
                if t >= half && (t - half) % self.cpb == 0 {
                    let k = (t - half) / self.cpb;
                    if k == 0 {
                        assert!(!l, "host receiver: start bit not low mid-bit");
                    } else if k <= 8 {
                        self.rx_bits |= (l as u16) << (k - 1);
                    } else {
                        if l {
                            self.received.push(self.rx_bits as u8);
                        } else {
                            self.host_ferr += 1;
                        }
                        self.rx_at = None;
                    }
                }
            }
        }
        self.last = l;
    }

    /// Complete reply lines received so far (each ending in CR or BEL),
    /// removed from `received`.
    pub fn take_lines(&mut self) -> Vec<String> {
        let mut out = vec![];
        while let Some(p) = self.received.iter().position(|&b| b == b'\r' || b == 7) {
            let l: Vec<u8> = self.received.drain(..=p).collect();
            out.push(String::from_utf8_lossy(&l).into_owned());
        }
        out
    }
}

#[derive(Clone)]
pub struct Shared(pub Rc<RefCell<SlcanSim>>);

impl Peer for Shared {
    fn tx(&self) -> bool {
        self.0.borrow().top.tx.val()
    }
    fn step(&mut self, bus: bool) {
        self.0.borrow_mut().step_bus(bus);
    }
}

/// A harness bus with `n` SJA1000 nodes and the slcan top as a peer.
pub fn net_with_slcan(n: usize, p: &SlcanParams) -> (Net, Rc<RefCell<SlcanSim>>) {
    let sim = Rc::new(RefCell::new(SlcanSim::new(p)));
    let mut net = Net::new(n);
    net.peer = Some(Box::new(Shared(sim.clone())));
    (net, sim)
}

/// Open node `i` with the Linux driver's sequence and the given timing.
pub fn open_node(net: &mut Net, i: usize, btr0: u8, btr1: u8) {
    net.drv[i].mode = CtrlMode::default();
    net.drv[i].auto = true;
    net.set_reset_mode(i);
    net.set_bittiming(i, btr0, btr1);
    net.start(i);
}

/// Send `line` + CR and run until `n` complete reply lines arrived (at
/// most `max` clocks); the lines.
#[track_caller]
pub fn command(net: &mut Net, sim: &Rc<RefCell<SlcanSim>>, line: &str, n: usize, max: usize) -> Vec<String> {
    let mut l = line.as_bytes().to_vec();
    l.push(b'\r');
    sim.borrow_mut().send(&l);
    collect(net, sim, n, max)
}

/// Run until `n` complete lines arrived (at most `max` clocks).
#[track_caller]
pub fn collect(net: &mut Net, sim: &Rc<RefCell<SlcanSim>>, n: usize, max: usize) -> Vec<String> {
    let mut got = vec![];
    let end = net.cycle + max;
    while got.len() < n {
        assert!(net.cycle < end, "only {} of {n} lines within {max} clocks: {got:?}", got.len());
        net.run(16);
        got.extend(sim.borrow_mut().take_lines());
    }
    got
}

/// The slcan line of a frame (as the adapter sends it).
pub fn line_of(f: &Frame) -> String {
    let mut s = String::new();
    s.push(match (f.ide, f.rtr) {
        (false, false) => 't',
        (true, false) => 'T',
        (false, true) => 'r',
        (true, true) => 'R',
    });
    if f.ide {
        s += &format!("{:08X}", f.id);
    } else {
        s += &format!("{:03X}", f.id);
    }
    s += &format!("{:X}", f.dlc.min(8));
    if !f.rtr {
        for b in &f.data {
            s += &format!("{b:02X}");
        }
    }
    s.push('\r');
    s
}
