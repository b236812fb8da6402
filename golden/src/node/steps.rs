//! [`GoldenNode::step`]'s per-mode work: the stuffed part of a frame, its fixed-form tail
//! (CRC delimiter to intermission) and error and overload flags (can-protocol.md).

use super::{FlagKind, FlagState, GoldenNode, Mode, D, R};
use crate::{ErrorKind, Event, FaultState, Field, ReqStatus, Role};

impl GoldenNode {
    /// Is the stuff bit that follows unstuffed bit `prev` inside the arbitration field for
    /// TEC exception 2 (§7)? Decided by the transmitter's own frame format.
    pub(super) fn stuff_in_arbitration(&self, prev: usize) -> bool {
        let Some(a) = &self.att else { return false };
        match a.bits[prev].field {
            Field::Identifier | Field::SrrBit | Field::ExIdentifier => true,
            Field::IdeBit => a.ext,
            Field::RtrBit => !a.ext,
            _ => false,
        }
    }

    pub(super) fn step_stuffed(&mut self, s: bool, drove: bool) {
        let tx = self.role == Role::Tx;
        if self.dec.stuff_next {
            if tx && s != drove {
                if drove == D {
                    self.error(ErrorKind::Bit, 8, 1);
                } else if self.stuff_in_arbitration(self.dec.bits.len() - 1) {
                    self.error(ErrorKind::Stuff, 0, 1);
                    self.ev.push(Event::Exc2);
                } else {
                    self.error(ErrorKind::Stuff, 8, 1);
                }
                return;
            }
            if !tx && s == self.dec.run_level {
                self.error(ErrorKind::Stuff, 8, 1);
                return;
            }
            self.dec.push_stuff(s);
        } else {
            let i = self.dec.bits.len();
            if tx && s != drove {
                let field = self.att.as_ref().map(|a| a.bits[i].field).unwrap_or(Field::Identifier);
                let arb = matches!(
                    field,
                    Field::Identifier | Field::SrrBit | Field::IdeBit | Field::ExIdentifier | Field::RtrBit
                );
                if drove == R && s == D && arb {
                    let pos = self.att.as_ref().map(|a| a.bits[i].pos as u32).unwrap_or(0);
                    self.ev.push(Event::ArbLost(pos));
                    self.attempt_failed();
                    self.role = Role::Rx;
                } else {
                    self.error(ErrorKind::Bit, 8, 1);
                    return;
                }
            }
            self.dec.push(s);
            if i == 0 {
                self.ev.push(Event::Sof);
            }
        }
        if self.dec.crc_done() && !self.dec.stuff_next {
            self.crc_err = self.dec.crc != self.dec.crc_rx;
            self.ack_drive = self.role == Role::Rx && !self.crc_err;
            self.mode = Mode::Tail { field: Field::CrcDelimiter, pos: 1 };
        }
    }

    pub(super) fn step_tail(&mut self, field: Field, pos: u32, s: bool, drove: bool) {
        let tx = self.role == Role::Tx;
        let next = |f| Mode::Tail { field: f, pos: 1 };
        match field {
            Field::CrcDelimiter => {
                if s == D {
                    self.error(ErrorKind::Form, 8, 1);
                } else {
                    self.mode = next(Field::AckSlot);
                }
            }
            Field::AckSlot => {
                if tx && s == R && !self.cfg.self_test {
                    if self.state == FaultState::ErrorPassive {
                        // Exception 1 is decided during the passive flag.
                        self.ev.push(Event::Error(ErrorKind::Ack));
                        self.attempt_failed();
                        self.start_flag(false, true);
                    } else {
                        self.error(ErrorKind::Ack, 8, 1);
                    }
                } else if !tx && drove == D && s == R {
                    self.error(ErrorKind::Bit, 8, 1);
                } else {
                    if !tx && drove == D && !self.cfg.rec_bosch_1999 {
                        // C13, ISO: the own ACK read back dominant is a successful reception.
                        self.reception_ok();
                    }
                    self.mode = next(Field::AckDelimiter);
                }
            }
            Field::AckDelimiter => {
                if !tx && self.crc_err {
                    self.error(ErrorKind::Crc, 8, 1);
                } else if s == D {
                    self.error(ErrorKind::Form, 8, 1);
                } else {
                    self.mode = next(Field::EndOfFrame);
                }
            }
            _ => {
                // End_Of_Frame
                if pos < 7 {
                    if s == D {
                        self.error(ErrorKind::Form, 8, 1);
                    } else {
                        self.mode = Mode::Tail { field, pos: pos + 1 };
                    }
                } else if tx {
                    if s == D {
                        self.error(ErrorKind::Form, 8, 1);
                    } else {
                        self.ev.push(Event::TxOk);
                        let id = self.att.take().map(|a| a.req_id);
                        if self.pending.as_ref().map(|p| p.2) == id {
                            self.pending = None;
                        }
                        self.set_req(ReqStatus::Done);
                        if !self.cfg.listen_only && self.tec > 0 {
                            self.tec -= 1;
                            self.update_state();
                        }
                        self.mode = Mode::Intermission { pos: 1 };
                    }
                } else {
                    let f = self.dec.frame();
                    self.ev.push(Event::RxOk(f));
                    // C13: with a dominant bit the frame is valid too and an overload frame
                    // follows; the 1999 rule counts the success in REC at a recessive bit
                    // only (the ISO rule counted it at the ACK slot).
                    if !self.cfg.listen_only && s == R && self.cfg.rec_bosch_1999 {
                        self.reception_ok();
                    }
                    if s == D {
                        self.start_overload();
                    } else {
                        self.mode = Mode::Intermission { pos: 1 };
                    }
                }
            }
        }
    }

    pub(super) fn step_flag(&mut self, mut fl: FlagState, s: bool, drove: bool) {
        if !fl.done {
            match fl.kind {
                FlagKind::Active | FlagKind::Overload => {
                    if drove == D && s == R {
                        // Bit error in an active or overload flag: +8, new flag typed from
                        // the state at this bit error, before the increment (C14).
                        self.ev.push(Event::Error(ErrorKind::Bit));
                        let before = self.state;
                        self.inc(8, 8);
                        if !self.bus_off() {
                            self.start_flag(before == FaultState::ErrorActive, false);
                        }
                        return;
                    }
                    if fl.pos >= 6 {
                        fl.done = true;
                    }
                }
                FlagKind::Passive => {
                    if fl.pos == 1 || s != fl.eq_level {
                        fl.eq_level = s;
                        fl.eq_cnt = 1;
                    } else {
                        fl.eq_cnt += 1;
                    }
                    if fl.exc1 && s == D && fl.pos <= 6 {
                        fl.exc1 = false;
                        self.add_tec(8);
                        if self.bus_off() {
                            return;
                        }
                    }
                    if fl.exc1 && fl.pos >= 6 {
                        fl.exc1 = false;
                        self.ev.push(Event::Exc1);
                    }
                    if fl.eq_cnt >= 6 {
                        fl.done = true;
                    }
                }
            }
            fl.pos += 1;
            self.mode = Mode::Flag(fl);
        } else if s == R {
            self.mode = Mode::Delim { overload: fl.kind == FlagKind::Overload, pos: 2 };
        } else {
            fl.daf += 1;
            fl.pos += 1;
            self.ev.push(Event::Daf(fl.daf));
            self.mode = Mode::Flag(fl);
            if self.role != Role::Tx && fl.kind != FlagKind::Overload && fl.daf == 1 {
                self.add_rec(8);
            }
            if fl.daf.is_multiple_of(8) {
                self.inc(8, 8);
            }
        }
    }
}
