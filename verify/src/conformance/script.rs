//! Bit records of the nodes and the scripted test-only transmitter with its
//! frame helpers (frames the RTL never sends: dominant SRR, recessive reserved
//! bits).

use super::*;

/// One bit as processed by a node.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BitRec {
    /// Time of the clock that carried the events (ps).
    pub t: u64,
    pub field: Field,
    pub pos: u32,
    pub stuff: bool,
    /// Transmitter role.
    pub tx_role: bool,
    /// Sampled level (true = recessive).
    pub level: bool,
    /// Level the node drove.
    pub drove: bool,
    /// `EV_*` event word.
    pub ev: u32,
    pub tec: u32,
    pub rec: u32,
    pub state: u32,
}

impl BitRec {
    pub fn has(&self, ev: usize) -> bool {
        (self.ev >> ev) & 1 == 1
    }
    /// Event names as in the can-protocol.md §18 trace.
    pub fn events(&self) -> String {
        let names = [
            (EV_SOF, "SOF"),
            (EV_ARB_LOST, "ARB_LOST"),
            (EV_BIT_ERR, "BIT_ERR"),
            (EV_STUFF_ERR, "STUFF_ERR"),
            (EV_CRC_ERR, "CRC_ERR"),
            (EV_FORM_ERR, "FORM_ERR"),
            (EV_ACK_ERR, "ACK_ERR"),
            (EV_AEF, "AEF"),
            (EV_PEF, "PEF"),
            (EV_OLF, "OLF"),
            (EV_OVL, "OVL"),
            (EV_DAF, "DAF"),
            (EV_TX_OK, "TX_OK"),
            (EV_RX_OK, "RX_OK"),
            (EV_EXC1, "EXC1"),
            (EV_EXC2, "EXC2"),
            (EV_RUN, "RUN"),
            (EV_RECOVERED, "RECOVERED"),
            (EV_INTEGRATED, "INTEGRATED"),
        ];
        let v: Vec<&str> = names.iter().filter(|(b, _)| self.has(*b)).map(|(_, n)| *n).collect();
        v.join(",")
    }
}

impl std::fmt::Display for BitRec {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{:>9} ns {}{} {}{} smp {} drv {} tec {} rec {} st {} [{}]",
            self.t / 1000,
            if self.field.has_role() { if self.tx_role { "Tx_" } else { "Rx_" } } else { "" },
            self.field.name(),
            self.pos,
            if self.stuff { "S" } else { "" },
            self.level as u8,
            self.drove as u8,
            self.tec,
            self.rec,
            self.state,
            self.events()
        )
    }
}

/// The plan's test-only transmitter: drives a precomputed bit sequence, one
/// level per `ntq` clocks, no synchronisation. It reads the bus (input 0)
/// only to start in step with another node's SOF ([`Scripted::send_with`]).
pub struct Scripted {
    name: String,
    clock: ClockSpec,
    ntq: u32,
    bits: Vec<bool>,
    idx: usize,
    cnt: u32,
    active: bool,
    wait_sof: bool,
    level: bool,
}

impl Scripted {
    pub fn new(name: &str, clock: ClockSpec, ntq: u32) -> Self {
        Scripted { name: name.to_string(), clock, ntq, bits: vec![], idx: 0, cnt: 0, active: false, wait_sof: false, level: true }
    }
    /// Start sending `bits` at the next clock.
    pub fn send(&mut self, bits: Vec<bool>) {
        self.bits = bits;
        self.idx = 0;
        self.cnt = 0;
        self.active = true;
        self.wait_sof = false;
    }
    /// Start sending `bits` when the bus goes dominant (another node's SOF).
    pub fn send_with(&mut self, bits: Vec<bool>) {
        self.send(bits);
        self.active = false;
        self.wait_sof = true;
    }
    /// Still sending (or waiting to)?
    pub fn busy(&self) -> bool {
        self.active || self.wait_sof
    }
}

impl Component for Scripted {
    fn name(&self) -> &str {
        &self.name
    }
    fn clock(&self) -> ClockSpec {
        self.clock
    }
    fn tick(&mut self, io: &mut Io<'_>) {
        if self.wait_sof && !io.input(0) {
            self.wait_sof = false;
            self.active = true;
            // The bus went dominant one clock ago: this SOF is one clock short.
            self.cnt = 1;
        }
        if self.active {
            self.level = self.bits[self.idx];
            self.cnt += 1;
            if self.cnt >= self.ntq {
                self.cnt = 0;
                self.idx += 1;
                if self.idx >= self.bits.len() {
                    self.active = false;
                }
            }
        } else {
            self.level = true;
        }
        io.set_output(0, self.level);
    }
}

/// Levels of frame `f` as a scripted transmitter sends it (ACK slot
/// recessive, up to the last EOF bit), with test-only options.
pub fn script_bits(f: &Frame, o: BuildOptions) -> Vec<bool> {
    bus_bits(f, o, false).iter().map(|b| b.level).collect()
}

/// The bus bit of frame `f` at (field, pos, stuff), if it exists.
pub fn frame_bit(f: &Frame, o: BuildOptions, field: Field, pos: u32, stuff: bool) -> Option<BusBit> {
    bus_bits(f, o, false).into_iter().find(|b| b.field == field && b.pos as u32 == pos && b.stuff == stuff)
}

/// Level of frame `f`'s bit at (field, pos, stuff) (true = recessive).
pub fn level_of(f: &Frame, field: Field, pos: u32, stuff: bool) -> Option<bool> {
    frame_bit(f, BuildOptions::default(), field, pos, stuff).map(|b| b.level)
}

/// The first frame of a deterministic family (extended or not, remote or
/// not) whose bus bits satisfy `pred`.
pub fn choose(ide: bool, rtr: bool, pred: impl Fn(&Frame) -> bool) -> Frame {
    let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
    let pats = [0x00u8, 0xFF, 0x0F, 0xF0, 0x1F, 0xF8, 0x83, 0x7C, 0x3E, 0xC1, 0x07, 0xE0];
    for _ in 0..400_000 {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        let id = if ide { (x >> 20) as u32 & 0x1FFF_FFFF } else { (x >> 20) as u32 & 0x7FF };
        let dlc = if (x >> 60) == 0 { 9 + ((x >> 56) % 7) as u8 } else { ((x >> 52) % 9) as u8 };
        let data: Vec<u8> = (0..dlc as usize)
            .map(|i| if (x >> (i + 8)) & 1 == 0 { pats[((x >> (2 * i)) % 12) as usize] } else { (x >> (5 * i + 3)) as u8 })
            .collect();
        let f = if rtr { Frame::remote(ide, id, dlc) } else { Frame::data(ide, id, dlc, &data) };
        if pred(&f) {
            return f;
        }
    }
    panic!("no frame meets the step's condition");
}

