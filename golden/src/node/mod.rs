//! [`GoldenNode`]: one CAN controller, processed bit by bit at its sample points
//! (can-protocol.md).

use super::frame::{unstuffed_bits, BitInfo, Frame, FrameVariant};
use super::{BitLabel, ErrorKind, Event, FaultState, Field, ReqStatus, Role};

mod confinement;
mod decoder;
mod steps;
use decoder::{rx_field, Decoder};

const D: bool = false;
const R: bool = true;

/// Operating options of a node (host configuration).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Config {
    /// Listen-only: never drives `D` (no ACK, no flags on the bus, no transmissions), counters
    /// unchanged; frames are still received and delivered.
    pub listen_only: bool,
    /// Self-test: a recessive ACK slot is not an ACK error for the transmitter.
    pub self_test: bool,
    /// Single-shot: no automatic retry after a lost arbitration or an error.
    pub single_shot: bool,
    /// Bus-off recovery waits for [`GoldenNode::start_recovery`] (SJA1000 style, C18).
    pub host_recovery: bool,
    /// C13: a receiver counts a successful reception in REC at a recessive End_Of_Frame
    /// bit 7 only, as the 1999 reference programs expect; by default (false) at the ACK
    /// slot once its own ACK was read back dominant (ISO 11898-1, ISO 16845-1 7.6.7,
    /// 7.6.8, 7.6.16).
    pub rec_bosch_1999: bool,
}

/// Result of processing one bit.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StepOut {
    /// Label of the processed bit.
    pub label: BitLabel,
    /// Level sampled (input of `step`).
    pub sampled: bool,
    /// Level this node drove during the processed bit.
    pub drove: bool,
    /// Level this node drives in the next bit.
    pub next_drive: bool,
    pub tec: u16,
    pub rec: u8,
    pub state: FaultState,
    pub events: Vec<Event>,
    /// Request status changes since the previous step, in order (host commands and this
    /// bit; trace `REQ` records).
    pub req: Vec<ReqStatus>,
}

impl StepOut {
    /// The frame delivered at this bit, if any.
    pub fn delivered(&self) -> Option<&Frame> {
        self.events.iter().find_map(|e| if let Event::RxOk(f) = e { Some(f) } else { None })
    }
    /// True if an event with the given §18 token occurred.
    pub fn has(&self, token: &str) -> bool {
        self.events.iter().any(|e| e.token() == token)
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum FlagKind {
    Active,
    Passive,
    Overload,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct FlagState {
    kind: FlagKind,
    /// POSITION of the current bit (1..6 flag, 7.. waiting for the first `R`).
    pos: u32,
    eq_level: bool,
    eq_cnt: u8,
    done: bool,
    daf: u32,
    /// TEC exception 1 undecided (passive ACK error, no `D` seen yet in flag bits 1..6).
    exc1: bool,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Mode {
    /// Held in reset by the host.
    Reset { pos: u32 },
    Integrate { cnt: u32 },
    Idle { pos: u32 },
    /// SOF .. CRC sequence (+ a final stuff bit): the decoder is active.
    Stuffed,
    /// CRC_Delimiter, ACK_Slot, ACK_Delimiter, End_Of_Frame.
    Tail { field: Field, pos: u32 },
    Flag(FlagState),
    /// Error or overload delimiter, POSITION 2..8.
    Delim { overload: bool, pos: u32 },
    Intermission { pos: u32 },
    Suspend { pos: u32 },
    /// `pos` = bits of the current run so far, `runs` = completed runs.
    BusOff { pos: u32, runs: u32 },
}

#[derive(Clone, Debug)]
struct Attempt {
    req_id: u64,
    ext: bool,
    bits: Vec<BitInfo>,
}

/// Behavioural CAN controller, stepped once per sample point. See the module docs.
#[derive(Clone, Debug)]
pub struct GoldenNode {
    cfg: Config,
    tec: u16,
    rec: u8,
    state: FaultState,
    warn: bool,
    mode: Mode,
    role: Role,
    drv: bool,
    pending: Option<(Frame, FrameVariant, u64)>,
    next_req_id: u64,
    att: Option<Attempt>,
    dec: Decoder,
    ack_drive: bool,
    crc_err: bool,
    recovery_started: bool,
    req_status: ReqStatus,
    req_log: Vec<ReqStatus>,
    ev: Vec<Event>,
}

impl Default for GoldenNode {
    fn default() -> Self {
        Self::new(Config::default())
    }
}

impl GoldenNode {
    /// A node just out of reset (Wait_For_Bus_Idle).
    pub fn new(cfg: Config) -> Self {
        GoldenNode {
            cfg,
            tec: 0,
            rec: 0,
            state: FaultState::ErrorActive,
            warn: false,
            mode: Mode::Integrate { cnt: 0 },
            role: Role::None,
            drv: R,
            pending: None,
            next_req_id: 0,
            att: None,
            dec: Decoder::default(),
            ack_drive: false,
            crc_err: false,
            recovery_started: false,
            req_status: ReqStatus::None,
            req_log: Vec::new(),
            ev: Vec::new(),
        }
    }

    /// Hardware reset: TEC = REC = 0, TX `R`, Wait_For_Bus_Idle; a pending request is dropped.
    pub fn reset(&mut self) {
        let cfg = self.cfg;
        let log = std::mem::take(&mut self.req_log);
        let dropped = matches!(self.req_status, ReqStatus::Pending | ReqStatus::Transmitting);
        *self = GoldenNode::new(cfg);
        self.req_log = log;
        if dropped {
            // the request is lost: reported as `error`, then no request
            self.req_log.push(ReqStatus::Error);
        }
    }

    pub fn config(&self) -> Config {
        self.cfg
    }
    /// Change the options (meant for use while idle or right after reset).
    pub fn set_config(&mut self, cfg: Config) {
        self.cfg = cfg;
        self.drv = self.compute_drive();
    }

    /// Request the transmission of `frame` (replaces a pending request not yet started).
    pub fn request(&mut self, frame: Frame) {
        self.request_variant(frame, FrameVariant::default());
    }
    /// Test-only: request a frame sent with a [`FrameVariant`] (dominant SRR, recessive r1/r0).
    pub fn request_variant(&mut self, frame: Frame, v: FrameVariant) {
        self.next_req_id += 1;
        self.pending = Some((frame, v, self.next_req_id));
        if self.req_status != ReqStatus::Transmitting {
            self.set_req(ReqStatus::Pending);
        }
    }
    /// Withdraw the request: a running attempt finishes, no further retries.
    pub fn withdraw(&mut self) {
        if self.pending.take().is_some() && self.req_status == ReqStatus::Pending {
            self.set_req(ReqStatus::Error);
        }
    }
    /// Hold the node in reset (`true`: counters cleared, TX `R`, FIELD `Reset`) or release it
    /// (`false`: integration starts, Wait_For_Bus_Idle).
    pub fn hold_reset(&mut self, on: bool) {
        if on {
            self.reset();
            self.mode = Mode::Reset { pos: 1 };
        } else if matches!(self.mode, Mode::Reset { .. }) {
            self.mode = Mode::Integrate { cnt: 0 };
        }
    }
    /// Lock-step rule §19.6: after REC dropped from above 127 on a successful reception, the
    /// checker may make the golden model adopt the DUT's value (119..=127).
    pub fn adopt_rec(&mut self, rec: u8) {
        assert!((119..=127).contains(&rec), "adopted REC must be 119..127");
        self.rec = rec;
        self.update_state();
        self.ev.clear();
    }
    /// Start bus-off recovery (only needed with [`Config::host_recovery`]).
    pub fn start_recovery(&mut self) {
        self.recovery_started = true;
    }

    /// Level driven in the current bit (`true` = recessive).
    pub fn drive(&self) -> bool {
        self.drv
    }
    pub fn tec(&self) -> u16 {
        self.tec
    }
    pub fn rec(&self) -> u8 {
        self.rec
    }
    pub fn state(&self) -> FaultState {
        self.state
    }
    /// Error warning: TEC ≥ 96 or REC ≥ 96 (C16).
    pub fn warning(&self) -> bool {
        self.warn
    }
    /// Is a transmit request pending?
    pub fn pending(&self) -> bool {
        self.pending.is_some()
    }
    pub fn req_status(&self) -> ReqStatus {
        self.req_status
    }
    /// Current role (kept through error/overload frames and the interframe space).
    pub fn role(&self) -> Role {
        self.role
    }
    /// Completed bus-off recovery runs (0 outside bus-off).
    pub fn recovery_runs(&self) -> u32 {
        if let Mode::BusOff { runs, .. } = self.mode {
            runs
        } else {
            0
        }
    }
    /// Still integrating after reset (Wait_For_Bus_Idle)?
    pub fn integrating(&self) -> bool {
        matches!(self.mode, Mode::Integrate { .. })
    }

    /// Hard synchronisation enabled for the current bit (§3.3).
    pub fn hs_en(&self) -> bool {
        match self.mode {
            Mode::Integrate { .. } | Mode::Idle { .. } | Mode::BusOff { .. } | Mode::Suspend { .. } => true,
            Mode::Intermission { pos } => pos == 3,
            Mode::Stuffed => self.dec.bits.is_empty(),
            _ => false,
        }
    }

    /// Label (role, FIELD, POSITION, stuff) of the current bit, the one `step` processes next.
    pub fn label(&self) -> BitLabel {
        let role = self.role;
        let (field, pos, stuff) = match self.mode {
            Mode::Reset { pos } => (Field::Reset, pos, false),
            Mode::Integrate { cnt } => (Field::WaitForBusIdle, cnt + 1, false),
            Mode::Idle { pos } => (Field::BusIdle, pos, false),
            Mode::BusOff { pos, .. } => (Field::BusOff, pos + 1, false),
            Mode::Stuffed => {
                let stuff = self.dec.stuff_next;
                let i = if stuff { self.dec.bits.len() - 1 } else { self.dec.bits.len() };
                let (f, p) = self.bit_field(i);
                (f, p, stuff)
            }
            Mode::Tail { field, pos } => (field, pos, false),
            Mode::Flag(fl) => {
                let f = match fl.kind {
                    FlagKind::Active => Field::ActiveErrorFlag,
                    FlagKind::Passive => Field::PassiveErrorFlag,
                    FlagKind::Overload => Field::OverloadFlag,
                };
                (f, fl.pos, false)
            }
            Mode::Delim { overload, pos } => {
                (if overload { Field::OverloadDelimiter } else { Field::ErrorDelimiter }, pos, false)
            }
            Mode::Intermission { pos } => (Field::Intermission, pos, false),
            Mode::Suspend { pos } => (Field::SuspendTransmission, pos, false),
        };
        let role = if field.is_bare() { Role::None } else { role };
        BitLabel { role, field, pos, stuff }
    }

    /// Field of unstuffed frame bit `i`: the transmitter labels by its own frame, a
    /// receiver by what it has received.
    fn bit_field(&self, i: usize) -> (Field, u32) {
        if self.role == Role::Tx {
            if let Some(a) = &self.att {
                let b = a.bits[i];
                return (b.field, b.pos as u32);
            }
        }
        rx_field(&self.dec.bits, i).unwrap_or((Field::CrcSequence, 15))
    }

    fn compute_drive(&self) -> bool {
        if self.cfg.listen_only {
            return R;
        }
        match self.mode {
            Mode::Stuffed if self.role == Role::Tx => {
                if self.dec.stuff_next {
                    !self.dec.run_level
                } else {
                    self.att.as_ref().map(|a| a.bits[self.dec.bits.len()].bit).unwrap_or(R)
                }
            }
            Mode::Tail { field: Field::AckSlot, .. } => !(self.role == Role::Rx && self.ack_drive),
            Mode::Flag(fl) => !(fl.kind != FlagKind::Passive && fl.pos <= 6),
            _ => R,
        }
    }

    fn attempt_failed(&mut self) {
        if self.att.take().is_some() || self.req_status == ReqStatus::Transmitting {
            self.set_req(if self.pending.is_some() { ReqStatus::Pending } else { ReqStatus::Error });
        }
    }

    /// An error detected at this bit: count it (`tx` for a transmitter, `rx` for a receiver),
    /// then start a flag with the next bit, typed from the state before the increment (§10).
    fn error(&mut self, kind: ErrorKind, tx: u16, rx: u8) {
        self.ev.push(Event::Error(kind));
        if self.role == Role::Tx {
            self.attempt_failed();
        }
        let before = self.state;
        self.inc(tx, rx);
        if self.bus_off() {
            return;
        }
        self.start_flag(before == FaultState::ErrorActive, false);
    }

    fn start_flag(&mut self, active: bool, exc1: bool) {
        let kind = if active { FlagKind::Active } else { FlagKind::Passive };
        self.ev.push(if active { Event::Aef } else { Event::Pef });
        self.mode = Mode::Flag(FlagState { kind, pos: 1, eq_level: R, eq_cnt: 0, done: false, daf: 0, exc1 });
    }

    fn start_overload(&mut self) {
        self.ev.push(Event::Ovl);
        self.ev.push(Event::Olf);
        self.mode = Mode::Flag(FlagState {
            kind: FlagKind::Overload,
            pos: 1,
            eq_level: R,
            eq_cnt: 0,
            done: false,
            daf: 0,
            exc1: false,
        });
    }

    // ---- frame start ---------------------------------------------------------------------

    fn set_req(&mut self, st: ReqStatus) {
        if st != self.req_status {
            self.req_status = st;
            self.req_log.push(st);
        }
    }

    fn may_transmit(&self) -> bool {
        self.pending.is_some() && !self.cfg.listen_only
    }

    fn begin_attempt(&mut self) {
        let (f, v, id) = self.pending.clone().expect("pending request");
        self.att = Some(Attempt { req_id: id, ext: f.ide, bits: unstuffed_bits(&f, v) });
        if self.cfg.single_shot {
            self.pending = None;
        }
        self.set_req(ReqStatus::Transmitting);
        self.role = Role::Tx;
        self.dec.clear();
        self.crc_err = false;
        self.ack_drive = false;
        self.mode = Mode::Stuffed;
    }

    /// The next bit may start a frame: SOF if a request is pending, else Bus_Idle.
    fn start_or_idle(&mut self, idle_pos: u32) {
        if self.may_transmit() {
            self.begin_attempt();
        } else {
            self.role = Role::None;
            self.mode = Mode::Idle { pos: idle_pos };
        }
    }

    /// A `D` sampled where a frame may start, as another node's SOF (or, at Intermission 3,
    /// as our own SOF if we may transmit there).
    fn sof_sampled(&mut self, own: bool) {
        if own {
            self.begin_attempt();
        } else {
            self.role = Role::Rx;
            self.att = None;
            self.dec.clear();
            self.crc_err = false;
            self.ack_drive = false;
            self.mode = Mode::Stuffed;
        }
        self.dec.push(D);
        self.ev.push(Event::Sof);
    }

    // ---- the bit processor ---------------------------------------------------------------

    /// Process the bit sampled at this node's sample point; returns what the node drives next.
    pub fn step(&mut self, s: bool) -> StepOut {
        let label = self.label();
        let drove = self.drv;
        self.ev.clear();
        match self.mode {
            Mode::Reset { pos } => self.mode = Mode::Reset { pos: pos + 1 },
            Mode::Integrate { cnt } => {
                if s == D {
                    self.mode = Mode::Integrate { cnt: 0 };
                } else if cnt + 1 >= 11 {
                    self.start_or_idle(1);
                } else {
                    self.mode = Mode::Integrate { cnt: cnt + 1 };
                }
            }
            Mode::Idle { pos } => {
                if s == D {
                    self.sof_sampled(false);
                } else {
                    self.start_or_idle(pos + 1);
                }
            }
            Mode::Stuffed => self.step_stuffed(s, drove),
            Mode::Tail { field, pos } => self.step_tail(field, pos, s, drove),
            Mode::Flag(fl) => self.step_flag(fl, s, drove),
            Mode::Delim { overload, pos } => {
                if s == D {
                    if pos < 8 {
                        self.error(ErrorKind::Form, 8, 1);
                    } else {
                        self.start_overload();
                    }
                } else if pos >= 8 {
                    self.mode = Mode::Intermission { pos: 1 };
                } else {
                    self.mode = Mode::Delim { overload, pos: pos + 1 };
                }
            }
            Mode::Intermission { pos } => {
                if pos < 3 {
                    if s == D {
                        self.start_overload();
                    } else {
                        self.mode = Mode::Intermission { pos: pos + 1 };
                    }
                } else if s == D {
                    // C15: an error-passive former transmitter owes a suspend.
                    let suspend_owed = self.state == FaultState::ErrorPassive && self.role == Role::Tx;
                    let own = self.may_transmit() && !suspend_owed;
                    self.sof_sampled(own);
                } else if self.state == FaultState::ErrorPassive && self.role == Role::Tx {
                    self.mode = Mode::Suspend { pos: 1 };
                } else {
                    self.start_or_idle(1);
                }
            }
            Mode::Suspend { pos } => {
                if s == D {
                    self.sof_sampled(false);
                } else if pos >= 8 {
                    self.start_or_idle(1);
                } else {
                    self.mode = Mode::Suspend { pos: pos + 1 };
                }
            }
            Mode::BusOff { pos, runs } => {
                if self.cfg.host_recovery && !self.recovery_started {
                    // frozen until the host starts recovery
                } else if s == D {
                    self.mode = Mode::BusOff { pos: 0, runs };
                } else if pos + 1 == 11 {
                    let runs = runs + 1;
                    self.ev.push(Event::Run(runs));
                    if runs >= 128 {
                        self.tec = 0;
                        self.rec = 0;
                        self.ev.push(Event::Recovered);
                        self.mode = Mode::Idle { pos: 1 };
                        self.update_state();
                        self.start_or_idle(1);
                    } else {
                        self.mode = Mode::BusOff { pos: 0, runs };
                    }
                } else {
                    self.mode = Mode::BusOff { pos: pos + 1, runs };
                }
            }
        }
        let next_drive = self.compute_drive();
        self.drv = next_drive;
        let req = std::mem::take(&mut self.req_log);
        StepOut {
            label,
            sampled: s,
            drove,
            next_drive,
            tec: self.tec,
            rec: self.rec,
            state: self.state,
            events: std::mem::take(&mut self.ev),
            req,
        }
    }
}
