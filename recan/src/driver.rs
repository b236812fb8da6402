//! The media-management driver of one node (recancentrate.md §2), a Rust
//! model run between kernel slices.
//!
//! The driver owns no controller: [`Driver::step`] gets the node's two
//! controllers ([`Ctrl`]) and the current time, drains their reports, and
//! runs the tx, rx and qua routines one at a time in report order (a qua found
//! in the same slice as an rx runs after it). A routine that waits K for the
//! other controller's report stays current until the report arrives or K has
//! passed; reports arriving meanwhile are queued (their own routines run
//! later, and find `FrameManaged` set when the waiting routine handled them).
//!
//! Reports are timestamped by the controller's clock edge; the driver reacts
//! at the end of the slice (a quarter bit), which models the host's latency.

use std::collections::VecDeque;

use canstar_controller::frame::Frame;
use canstar_controller::fsm::Field;

use crate::ctrl::{Ctrl, CtrlEvent};
use crate::spec::DriverSpec;

/// Why a controller was quarantined.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum QuaReason {
    Tec,
    Rec,
    Timer,
}

#[derive(Clone, Debug, PartialEq)]
enum Routine {
    Tx { ctrl: usize, t: u64 },
    Rx { ctrl: usize, t: u64, frame: Frame },
    Qua { ctrl: usize, reason: QuaReason },
}

#[derive(Clone, Debug)]
struct Wait {
    routine: Routine,
    deadline: u64,
}

/// What a driver tells its application and the run.
#[derive(Clone, Debug, PartialEq)]
pub enum Notice {
    /// The pending frame was sent (at this time).
    TxSuccess(u64),
    /// A frame of another node, delivered once.
    Deliver(Frame),
    /// A controller was quarantined.
    Quarantined { ctrl: usize, t: u64, reason: QuaReason },
    /// The pending frame was requested again after an omission discrepancy.
    Retransmit,
    /// The pending frame was requested on a new tx controller.
    Rerequest,
    /// No active controller is left.
    NoController,
    /// The pending frame, after `max_inconsists` omission discrepancies, was requested on
    /// the non-tx controller too (`DriverSpec::copy_tec`).
    Copy,
    /// A copy was given up unsent (its controller failed or the timer expired).
    CopyGivenUp,
    /// The tx controller was quarantined after its last frame was reported sent on the
    /// omission rule alone: that frame is sent again on the new tx controller first.
    Resend,
}

/// State of one node's driver.
pub struct Driver {
    pub node: usize,
    spec: DriverSpec,
    k_ps: u64,
    timeout_ps: u64,
    pub active: [bool; 2],
    /// The tx controller (None when no controller is active).
    pub tx: Option<usize>,
    pub frame_managed: bool,
    pub msg_tx_omi: u32,
    /// The pending frame (`TxPending` = `pending.is_some()`).
    pub pending: Option<Frame>,
    /// When the pending frame was requested.
    pub pending_since: Option<u64>,
    /// The tx controller reported the transmission of the pending frame.
    tx_reported: bool,
    timer: Option<u64>,
    /// Last report per controller: (time, frame) of the last reception, time of the last transmission.
    rx_flag: [Option<(u64, Frame)>; 2],
    tx_flag: [Option<u64>; 2],
    queue: VecDeque<Routine>,
    wait: Option<Wait>,
    /// Retransmissions of the pending frame so far.
    pub retx_this_frame: u32,
    /// Reports not yet seen by the host (interrupt latency).
    inbox: Vec<(u64, usize, CtrlEvent)>,
    latency_ps: u64,
    /// When each controller's TEC or REC was first seen at the warning limit.
    warn_since: [Option<(u64, QuaReason)>; 2],
    /// The controller sending a copy of the pending frame (`DriverSpec::copy_tec`); the
    /// frame is reported sent when the copy is.
    copy_on: Option<usize>,
    /// The last frame copied and the controller that sends the copy: the other controller
    /// receiving that frame is receiving this node's copy (once; forgotten when the
    /// application requests the same frame again, so a copy that never reached the other
    /// star cannot hide a later reception of the node's own frame).
    copied: Option<(Frame, usize)>,
    /// A copy was given up unsent: no copy until the non-tx controller reports a reception.
    copy_blocked: bool,
    /// The last frame reported sent on the omission rule alone (`MsgTxOmi` at
    /// `maxInconsists`): the other controller never saw it. None once a later frame is
    /// reported sent, or once it has been sent again.
    unconfirmed: Option<Frame>,
    /// The application's frame waiting while the unconfirmed frame is sent again on a new
    /// tx controller (requested when that one is reported sent).
    deferred: Option<Frame>,
    /// The pending frame is the unconfirmed frame sent again: its success is not the
    /// application's.
    resending: bool,
    /// The tx controller reported a transmit error after the CRC (delimiter, ACK, EOF)
    /// since its frame was requested: receivers may have accepted that frame, so the
    /// unconfirmed frame before it is not sent again.
    late_tx_error: bool,
    /// Routine log (only with tracing).
    pub log: Option<Vec<String>>,
}

impl Driver {
    pub fn new(node: usize, spec: &DriverSpec, bit_time_ps: u64, initial_tx: usize, trace: bool) -> Self {
        Driver {
            node,
            spec: spec.clone(),
            k_ps: (spec.k_bits * bit_time_ps as f64).round() as u64,
            timeout_ps: spec.tx_timeout_ps(),
            active: [true, true],
            tx: Some(initial_tx),
            frame_managed: false,
            msg_tx_omi: 0,
            pending: None,
            pending_since: None,
            tx_reported: false,
            timer: None,
            rx_flag: [None, None],
            tx_flag: [None, None],
            queue: VecDeque::new(),
            wait: None,
            retx_this_frame: 0,
            inbox: Vec::new(),
            latency_ps: (spec.irq_latency_ns * 1000.0).round() as u64,
            warn_since: [None, None],
            copy_on: None,
            copied: None,
            copy_blocked: false,
            unconfirmed: None,
            deferred: None,
            resending: false,
            late_tx_error: false,
            log: trace.then(Vec::new),
        }
    }

    fn note(&mut self, now: u64, s: impl FnOnce() -> String) {
        if let Some(l) = &mut self.log {
            l.push(format!("{:>10.3} us node {}: {}", now as f64 / 1e6, self.node, s()));
        }
    }

    /// Is a routine running or queued?
    pub fn busy(&self) -> bool {
        self.wait.is_some() || !self.queue.is_empty()
    }

    /// tx request (application): refused (false) if a frame is pending or no
    /// controller is active.
    pub fn tx_request(&mut self, f: Frame, now: u64, ctrls: &mut [&mut Ctrl; 2]) -> bool {
        if self.pending.is_some() {
            return false;
        }
        let Some(tx) = self.tx else { return false };
        if self.copied.as_ref().is_some_and(|(g, _)| *g == f) {
            self.copied = None;
        }
        ctrls[tx].request(f.clone());
        self.note(now, || format!("tx request {:#x}[{:?}] on {}", f.id, f.data, "AB".as_bytes()[tx] as char));
        self.pending = Some(f);
        self.pending_since = Some(now);
        self.tx_reported = false;
        self.late_tx_error = false;
        self.retx_this_frame = 0;
        self.timer = Some(now + self.timeout_ps);
        true
    }

    /// Drain the controllers' reports, check the warning limit and the timer,
    /// and run routines. Returns what happened.
    pub fn step(&mut self, now: u64, ctrls: &mut [&mut Ctrl; 2]) -> Vec<Notice> {
        let mut out = Vec::new();
        // 1. reports, in time order across both controllers, once the
        //    interrupt latency has passed
        for (c, ctrl) in ctrls.iter_mut().enumerate() {
            if ctrl.has_events() {
                for (t, e) in ctrl.take_events() {
                    self.inbox.push((t, c, e));
                }
            }
        }
        let lat = self.latency_ps;
        let mut evs: Vec<(u64, usize, CtrlEvent)> = Vec::new();
        if !self.inbox.is_empty() {
            let (due, later): (Vec<_>, Vec<_>) = std::mem::take(&mut self.inbox).into_iter().partition(|e| e.0 + lat <= now);
            self.inbox = later;
            evs = due;
        }
        evs.sort_by_key(|e| (e.0, e.1));
        for (t, c, e) in evs {
            if !self.active[c] {
                continue;
            }
            match e {
                CtrlEvent::TxDone(_) if self.tx != Some(c) => {
                    // only a copy is ever requested on the non-tx controller (a new tx
                    // controller is chosen before the pending frame is requested on it)
                    self.note(t, || format!("copy sent by {}", abc(c)));
                    if self.copy_on == Some(c) {
                        self.copy_on = None;
                        self.success(now, &mut out);
                        self.note(now, || "copy sent: success".into());
                    }
                }
                CtrlEvent::TxDone(_) => {
                    self.tx_flag[c] = Some(t);
                    if Some(c) == self.tx {
                        self.tx_reported = true;
                    }
                    self.queue.push_back(Routine::Tx { ctrl: c, t });
                }
                CtrlEvent::Rx(f) => {
                    if self.tx != Some(c) {
                        self.copy_blocked = false;
                    }
                    self.rx_flag[c] = Some((t, f.clone()));
                    self.queue.push_back(Routine::Rx { ctrl: c, t, frame: f });
                }
                CtrlEvent::Error { tx: true, field } if self.tx == Some(c) && after_crc(field) => {
                    self.late_tx_error = true;
                    self.note(t, || format!("tx error on {} in {field:?}: the frame may have been taken", abc(c)));
                }
                CtrlEvent::Error { tx, field } => {
                    self.note(t, || format!("error on {} (tx {tx}) in {field:?}", abc(c)));
                }
            }
        }
        // 2. error warning limit (seen after the interrupt latency; after the
        //    receptions of this slice)
        for (c, ctrl) in ctrls.iter().enumerate() {
            if self.active[c] && !ctrl.is_crashed() {
                let (tec, rec) = (ctrl.tec(), ctrl.rec());
                let lim = self.spec.warning_limit;
                if self.warn_since[c].is_none() && (tec >= lim || rec >= lim) {
                    let reason = if tec >= lim { QuaReason::Tec } else { QuaReason::Rec };
                    self.warn_since[c] = Some((now, reason));
                }
                if let Some((t, reason)) = self.warn_since[c] {
                    if t + lat <= now && !self.queue.iter().any(|r| matches!(r, Routine::Qua { ctrl, .. } if *ctrl == c)) {
                        self.queue.push_back(Routine::Qua { ctrl: c, reason });
                    }
                }
            }
        }
        // 3. a copy whose controller fails or runs out of time is given up
        if let Some(o) = self.copy_on {
            let late = self.timer.is_some_and(|t| now >= t);
            if late || !self.active[o] || ctrls[o].tec() >= self.spec.copy_tec {
                ctrls[o].withdraw();
                self.copy_on = None;
                self.copy_blocked = true;
                self.note(now, || format!("copy on {} given up, success", abc(o)));
                out.push(Notice::CopyGivenUp);
                self.success(now, &mut out);
            }
        }
        // 4. transmission timer
        if let (Some(t), Some(tx)) = (self.timer, self.tx) {
            if now >= t {
                self.timer = None;
                self.queue.push_back(Routine::Qua { ctrl: tx, reason: QuaReason::Timer });
            }
        }
        // 5. routines
        loop {
            if let Some(w) = self.wait.take() {
                match self.resume(w, now, ctrls, &mut out) {
                    Some(w) => {
                        self.wait = Some(w);
                        break;
                    }
                    None => continue,
                }
            }
            let Some(r) = self.queue.pop_front() else { break };
            if let Some(w) = self.start(r, now, ctrls, &mut out) {
                self.wait = Some(w);
            }
        }
        // 6. the application's frame after a frame sent again
        if self.pending.is_none() {
            if let (Some(f), Some(tx)) = (self.deferred.take(), self.tx) {
                ctrls[tx].request(f.clone());
                self.note(now, || format!("deferred {:#x}[{:?}] requested on {}", f.id, f.data, abc(tx)));
                self.pending = Some(f);
                self.tx_reported = false;
                self.late_tx_error = false;
                self.timer = Some(now + self.timeout_ps);
            }
        }
        out
    }

    /// Did controller `c` report a transmission at or after `since`?
    fn tx_seen(&self, c: usize, since: u64) -> bool {
        self.tx_flag[c].is_some_and(|t| t >= since)
    }
    /// Did controller `c` report the reception of `f` at or after `since`?
    fn rx_seen(&self, c: usize, since: u64, f: Option<&Frame>) -> bool {
        match &self.rx_flag[c] {
            Some((t, g)) => *t >= since && f.is_none_or(|f| f == g),
            None => false,
        }
    }

    fn start(&mut self, r: Routine, now: u64, ctrls: &mut [&mut Ctrl; 2], out: &mut Vec<Notice>) -> Option<Wait> {
        match &r {
            Routine::Tx { ctrl, .. } => {
                if !self.active[*ctrl] {
                    return None;
                }
                self.timer = None;
                if self.frame_managed {
                    self.frame_managed = false;
                    self.note(now, || format!("tx routine {}: managed", abc(*ctrl)));
                    return None;
                }
                let deadline = now + self.k_ps;
                self.resume(Wait { routine: r, deadline }, now, ctrls, out)
            }
            Routine::Rx { ctrl, frame, .. } => {
                if !self.active[*ctrl] {
                    return None;
                }
                if self.copied.as_ref().is_some_and(|(g, s)| g == frame && s != ctrl) {
                    self.copied = None;
                    self.note(now, || format!("rx routine {}: this node's copy", abc(*ctrl)));
                    return None;
                }
                if self.frame_managed {
                    self.frame_managed = false;
                    self.note(now, || format!("rx routine {}: managed", abc(*ctrl)));
                    return None;
                }
                let deadline = now + self.k_ps;
                self.resume(Wait { routine: r, deadline }, now, ctrls, out)
            }
            Routine::Qua { ctrl, reason } => {
                let c = *ctrl;
                if !self.active[c] {
                    return None;
                }
                self.active[c] = false;
                ctrls[c].deactivate();
                out.push(Notice::Quarantined { ctrl: c, t: now, reason: *reason });
                self.note(now, || format!("qua routine {} ({reason:?}): deactivated", abc(c)));
                if self.tx == Some(c) {
                    self.timer = None;
                    let o = 1 - c;
                    if self.active[o] {
                        self.tx = Some(o);
                        // a copy on the new tx controller is its transmission now, timed
                        // like any other
                        if self.copy_on.take() == Some(o) {
                            self.timer = Some(now + self.timeout_ps);
                        }
                        // send again (hub.md §5.30): a frame is pending that the old tx
                        // controller did not report sent, and its last frame was reported on
                        // the omission rule alone; the quarantine says the old controller's
                        // star was the faulty one, so that frame goes first
                        let again = self.spec.resend_unconfirmed
                            && self.pending.is_some()
                            && !self.tx_reported
                            && !self.resending
                            && !self.late_tx_error;
                        let unconfirmed = self.unconfirmed.take().filter(|_| again);
                        if let Some(u) = unconfirmed {
                            self.deferred = self.pending.take();
                            ctrls[o].request(u.clone());
                            self.note(now, || format!("unconfirmed {:#x}[{:?}] sent again on {}", u.id, u.data, abc(o)));
                            self.pending = Some(u);
                            self.resending = true;
                            self.late_tx_error = false;
                            self.tx_reported = false;
                            self.timer = Some(now + self.timeout_ps);
                            out.push(Notice::Resend);
                        } else if let Some(f) = self.pending.clone() {
                            if !self.tx_reported {
                                ctrls[o].request(f);
                                self.timer = Some(now + self.timeout_ps);
                                out.push(Notice::Rerequest);
                                self.note(now, || format!("pending frame requested on {}", abc(o)));
                            }
                        }
                    } else {
                        self.tx = None;
                        out.push(Notice::NoController);
                    }
                }
                None
            }
        }
    }

    /// Continue a waiting routine: finish it (None) or keep waiting.
    fn resume(&mut self, w: Wait, now: u64, ctrls: &mut [&mut Ctrl; 2], out: &mut Vec<Notice>) -> Option<Wait> {
        let k = self.k_ps;
        match &w.routine {
            Routine::Tx { ctrl, t } => {
                let (c, o) = (*ctrl, 1 - *ctrl);
                let since = t.saturating_sub(k);
                if self.rx_seen(o, since, self.pending.as_ref()) {
                    self.frame_managed = true;
                    self.success(now, out);
                    self.note(now, || format!("tx routine {}: other rx seen, success", abc(c)));
                    return None;
                }
                if now < w.deadline {
                    return Some(w);
                }
                // omission discrepancy
                let (a, b) = (&ctrls[0], &ctrls[1]);
                self.note(now, || format!("tx routine {}: omission discrepancy, TEC/REC A {:?} B {:?}", abc(c), (a.tec(), a.rec()), (b.tec(), b.rec())));
                if self.msg_tx_omi >= self.spec.max_inconsists {
                    if self.copy_to_other_star(c, now, ctrls, out) {
                        self.note(now, || format!("tx routine {}: omission, MsgTxOmi at max, copy requested", abc(c)));
                    } else {
                        let f = self.pending.clone();
                        self.success(now, out);
                        self.unconfirmed = f;
                        self.note(now, || format!("tx routine {}: omission, MsgTxOmi at max, success", abc(c)));
                    }
                } else {
                    self.msg_tx_omi += 1;
                    if let Some(f) = self.pending.clone() {
                        if self.active[c] && self.tx == Some(c) {
                            ctrls[c].request(f);
                            self.tx_reported = false;
                            self.timer = Some(now + self.timeout_ps);
                            self.retx_this_frame += 1;
                            out.push(Notice::Retransmit);
                        }
                    }
                    let m = self.msg_tx_omi;
                    self.note(now, || format!("tx routine {}: omission {m}, retransmit", abc(c)));
                }
                None
            }
            Routine::Rx { ctrl, t, frame } => {
                let (c, o) = (*ctrl, 1 - *ctrl);
                let since = t.saturating_sub(k);
                if self.pending.as_ref() == Some(frame) && self.tx_seen(o, since) {
                    self.frame_managed = true;
                    self.success(now, out);
                    self.note(now, || format!("rx routine {}: own frame, other tx seen, success", abc(c)));
                    return None;
                }
                if now < w.deadline {
                    return Some(w);
                }
                if self.pending.as_ref() == Some(frame) {
                    self.msg_tx_omi += 1;
                    let m = self.msg_tx_omi;
                    self.note(now, || format!("rx routine {}: own frame without tx report, omission {m}", abc(c)));
                    return None;
                }
                if self.active[o] && self.rx_seen(o, since, Some(frame)) {
                    self.frame_managed = true;
                }
                let fm = self.frame_managed;
                self.note(now, || format!("rx routine {}: deliver {:#x}[{:?}] (managed {fm})", abc(c), frame.id, frame.data));
                out.push(Notice::Deliver(frame.clone()));
                None
            }
            Routine::Qua { .. } => None,
        }
    }

    /// `DriverSpec::copy_tec`: the tx controller `c` has had transmit errors lately and the
    /// other one has not; request the pending frame on the other one as well and report it
    /// sent when the copy is (so the next frame cannot overtake the copy). The copy is given
    /// up, and the frame reported sent, when the other controller's TEC reaches `copy_tec`,
    /// it is quarantined, or the transmission timer expires; then no copy is made until the
    /// other controller reports a reception. Returns whether a copy was requested.
    fn copy_to_other_star(&mut self, c: usize, now: u64, ctrls: &mut [&mut Ctrl; 2], out: &mut Vec<Notice>) -> bool {
        let (o, lim) = (1 - c, self.spec.copy_tec);
        let Some(f) = self.pending.clone() else { return false };
        if lim == 0 || self.copy_blocked || !self.active[o] || ctrls[c].tec() < lim || ctrls[o].tec() >= lim {
            return false;
        }
        ctrls[o].request(f.clone());
        self.note(now, || format!("copy of {:#x}[{:?}] requested on {}", f.id, f.data, abc(o)));
        self.copy_on = Some(o);
        self.copied = Some((f, o));
        self.timer = Some(now + self.timeout_ps);
        out.push(Notice::Copy);
        true
    }

    fn success(&mut self, now: u64, out: &mut Vec<Notice>) {
        self.msg_tx_omi = if self.msg_tx_omi >= self.spec.max_inconsists && !self.frame_managed {
            self.msg_tx_omi
        } else {
            0
        };
        self.timer = None;
        self.unconfirmed = None;
        if std::mem::take(&mut self.resending) {
            self.pending = None;
            return;
        }
        self.pending_since = None;
        if self.pending.take().is_some() {
            out.push(Notice::TxSuccess(now));
        }
    }
}

/// A transmitter's error in these fields comes after receivers may have taken the frame
/// as valid (they accept it at the last but one EOF bit; an error flag may not reach them).
fn after_crc(f: Field) -> bool {
    matches!(f, Field::CrcDel | Field::AckSlot | Field::AckDel | Field::Eof)
}

fn abc(c: usize) -> char {
    if c == 0 {
        'A'
    } else {
        'B'
    }
}

#[cfg(test)]
mod tests;
