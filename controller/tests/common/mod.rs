//! Bit-level multi-node harness: several `CanFsm` blocks on one wired-AND
//! bus, one bit per clock (`sample` held high), with per-node receive
//! overrides as in can-protocol.md §1.
#![allow(dead_code)]

pub mod core_bus;
pub mod stim;

use canstar_controller::frame::Frame;
use canstar_controller::fsm::*;
use canstar_hdl::drive;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ovr {
    None,
    Invert,
    StuckR,
    StuckD,
}

/// What one node did in one bit.
#[derive(Clone, Debug)]
pub struct Rec {
    pub bit: usize,
    pub field: Field,
    pub pos: u8,
    pub stuff: bool,
    pub role_tx: bool,
    pub smp: bool,
    pub drv: bool,
    pub ev: u64,
    pub tec: u64,
    pub rec: u64,
    pub state: u64,
}

impl Rec {
    pub fn has(&self, ev: usize) -> bool {
        (self.ev >> ev) & 1 == 1
    }
    pub fn is(&self, f: Field, pos: u8) -> bool {
        self.field == f && self.pos == pos && !self.stuff
    }
}

pub struct Bus {
    pub nodes: Vec<Box<CanFsm>>,
    pub ovr: Vec<Ovr>,
    pub log: Vec<Vec<Rec>>,
    pub rx: Vec<Vec<Frame>>,
    pub bit: usize,
    pub bus_log: Vec<bool>,
    /// A scripted transmitter: levels wired-AND into the bus, one per bit.
    pub script: std::collections::VecDeque<bool>,
}

pub fn set_frame(n: &mut CanFsm, f: &Frame) {
    n.tx_ide.next = f.ide;
    n.tx_rtr.next = f.rtr;
    n.tx_id.next = (f.id as u64).into();
    n.tx_dlc.next = (f.dlc as u64).into();
    n.tx_data.next = f.data_word().into();
}

impl Bus {
    pub fn new(n: usize) -> Bus {
        let mut nodes = Vec::new();
        for _ in 0..n {
            let mut u = Box::new(CanFsm::new());
            drive::init(&mut *u);
            u.reset.next = true;
            u.sample.next = false;
            u.busmon.next = true;
            drive::cycle(&mut *u);
            u.reset.next = false;
            u.sample.next = true;
            nodes.push(u);
        }
        Bus {
            ovr: vec![Ovr::None; n],
            log: vec![vec![]; n],
            rx: vec![vec![]; n],
            nodes,
            bit: 0,
            bus_log: vec![],
            script: Default::default(),
        }
    }

    /// A bus whose nodes have integrated (11 recessive bits).
    pub fn integrated(n: usize) -> Bus {
        let mut b = Bus::new(n);
        b.run(12);
        for i in 0..n {
            assert_eq!(b.field(i), Field::Idle, "node {i} did not integrate");
        }
        b
    }

    pub fn field(&self, i: usize) -> Field {
        Field::from_code(self.nodes[i].field.val().index() as u64).unwrap()
    }
    pub fn tec(&self, i: usize) -> u64 {
        self.nodes[i].tec.val().index() as u64
    }
    pub fn rec(&self, i: usize) -> u64 {
        self.nodes[i].rec.val().index() as u64
    }
    pub fn state(&self, i: usize) -> u64 {
        self.nodes[i].state.val().index() as u64
    }

    pub fn request(&mut self, i: usize, f: &Frame) {
        set_frame(&mut self.nodes[i], f);
        self.nodes[i].tx_req.next = true;
    }
    pub fn withdraw(&mut self, i: usize) {
        self.nodes[i].tx_req.next = false;
    }

    /// One bit.
    pub fn step(&mut self) {
        let bus = self.nodes.iter().all(|n| n.drive.val()) & self.script.pop_front().unwrap_or(true);
        self.bus_log.push(bus);
        let mut pre = Vec::new();
        for (i, n) in self.nodes.iter_mut().enumerate() {
            let smp = match self.ovr[i] {
                Ovr::None => bus,
                Ovr::Invert => !bus,
                Ovr::StuckR => true,
                Ovr::StuckD => false,
            };
            pre.push((
                Field::from_code(n.field.val().index() as u64).unwrap(),
                n.pos.val().index() as u8,
                n.stuff.val(),
                n.role.val(),
                smp,
                n.drive.val(),
            ));
            n.busmon.next = smp;
            n.sample.next = true;
            drive::cycle(&mut **n);
        }
        for (i, n) in self.nodes.iter().enumerate() {
            let (field, pos, stuff, role_tx, smp, drv) = pre[i];
            let ev = n.events.val().index() as u64;
            let r = Rec {
                bit: self.bit,
                field,
                pos,
                stuff,
                role_tx,
                smp,
                drv,
                ev,
                tec: n.tec.val().index() as u64,
                rec: n.rec.val().index() as u64,
                state: n.state.val().index() as u64,
            };
            if n.rx_valid.val() {
                self.rx[i].push(Frame::from_native(
                    n.rx_ide.val(),
                    n.rx_rtr.val(),
                    n.rx_id.val().index() as u32,
                    n.rx_dlc.val().index() as u8,
                    n.rx_data.val().to_u64(),
                ));
            }
            self.log[i].push(r);
        }
        self.bit += 1;
    }

    pub fn run(&mut self, bits: usize) {
        for _ in 0..bits {
            self.step();
        }
    }

    /// Run until `pred` holds after a bit (checked after every bit); panics after `max` bits.
    #[track_caller]
    pub fn run_until(&mut self, max: usize, mut pred: impl FnMut(&Bus) -> bool) {
        for _ in 0..max {
            self.step();
            if pred(self) {
                return;
            }
        }
        panic!("condition not reached within {max} bits");
    }

    /// Run until node `i` is about to process the bit (field, pos) (non-stuff).
    pub fn run_to(&mut self, i: usize, f: Field, pos: u8, max: usize) {
        for _ in 0..max {
            if self.field(i) == f && self.nodes[i].pos.val().index() as u8 == pos && !self.nodes[i].stuff.val() {
                return;
            }
            self.step();
        }
        panic!("node {i} did not reach {:?} {pos} within {max} bits", f);
    }

    /// Run until all nodes are in Bus_Idle.
    pub fn run_idle(&mut self, max: usize) {
        self.run_until(max, |b| (0..b.nodes.len()).all(|i| b.field(i) == Field::Idle));
    }

    /// Force node `i`'s receive path for the next bit only.
    pub fn force_bit(&mut self, i: usize, o: Ovr) {
        self.ovr[i] = o;
        self.step();
        self.ovr[i] = Ovr::None;
    }

    /// Records of node `i` having event `ev` since bit `from`.
    pub fn events(&self, i: usize, ev: usize, from: usize) -> Vec<&Rec> {
        self.log[i].iter().filter(|r| r.bit >= from && r.has(ev)).collect()
    }

    /// Print the trace of node `i` (debugging).
    pub fn dump(&self, i: usize, from: usize) {
        for r in self.log[i].iter().filter(|r| r.bit >= from) {
            eprintln!(
                "{:5} N{} {}{:<20} {:3} {} smp={} drv={} tec={} rec={} st={} ev={:#07x}",
                r.bit,
                i,
                if r.field.has_role() { if r.role_tx { "Tx_" } else { "Rx_" } } else { "" },
                r.field.name(),
                r.pos,
                if r.stuff { "S" } else { "-" },
                r.smp as u8,
                r.drv as u8,
                r.tec,
                r.rec,
                r.state,
                r.ev
            );
        }
    }
}

impl Bus {
    /// Run until node `i` is about to process the stuff bit that follows (field, pos).
    pub fn run_to_stuff(&mut self, i: usize, f: Field, pos: u8, max: usize) {
        for _ in 0..max {
            if self.field(i) == f && self.nodes[i].pos.val().index() as u8 == pos && self.nodes[i].stuff.val() {
                return;
            }
            self.step();
        }
        panic!("node {i} did not reach the stuff bit after {:?} {pos} within {max} bits", f);
    }
    /// Force node `i` for `n` bits starting at its bit (field, pos).
    pub fn force_at(&mut self, i: usize, f: Field, pos: u8, o: Ovr, n: usize) {
        self.run_to(i, f, pos, 2000);
        self.ovr[i] = o;
        self.run(n);
        self.ovr[i] = Ovr::None;
    }
    /// The last record of node `i`.
    pub fn last(&self, i: usize) -> &Rec {
        self.log[i].last().unwrap()
    }
}
