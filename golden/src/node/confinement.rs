//! Fault confinement of the golden node (can-protocol.md §13): TEC, REC, the error
//! states, the warning limit and the entry into bus-off.

use super::*;

impl GoldenNode {
    pub(super) fn update_state(&mut self) {
        let new = if self.tec > 255 {
            FaultState::BusOff
        } else if self.tec >= 128 || self.rec >= 128 {
            FaultState::ErrorPassive
        } else {
            FaultState::ErrorActive
        };
        if new != self.state {
            self.state = new;
            self.ev.push(match new {
                FaultState::ErrorActive => Event::ToEa,
                FaultState::ErrorPassive => Event::ToEp,
                FaultState::BusOff => Event::ToBo,
            });
        }
        let w = self.tec >= 96 || self.rec >= 96;
        if w != self.warn {
            self.warn = w;
            self.ev.push(if w { Event::Warn } else { Event::WarnClr });
        }
        if new == FaultState::BusOff && !matches!(self.mode, Mode::BusOff { .. }) {
            self.enter_bus_off();
        }
    }

    pub(super) fn enter_bus_off(&mut self) {
        self.mode = Mode::BusOff { pos: 0, runs: 0 };
        self.role = Role::None;
        self.att = None;
        self.recovery_started = false;
        if self.req_status == ReqStatus::Transmitting {
            self.set_req(if self.pending.is_some() { ReqStatus::Pending } else { ReqStatus::Error });
        }
    }

    pub(super) fn add_tec(&mut self, n: u16) {
        if self.cfg.listen_only || n == 0 {
            return;
        }
        self.tec += n;
        self.update_state();
    }

    /// A successful reception in REC: − 1, or 127 from 128 and above (C11, C13).
    pub(super) fn reception_ok(&mut self) {
        if self.rec >= 128 {
            self.rec = 127;
        } else if self.rec > 0 {
            self.rec -= 1;
        }
        self.update_state();
    }

    pub(super) fn add_rec(&mut self, n: u8) {
        if self.cfg.listen_only || n == 0 {
            return;
        }
        if self.rec <= 127 {
            self.rec += n; // C12: increments while REC >= 128 are not applied
        }
        self.update_state();
    }

    /// Counter increment by role: `tx` to TEC for a transmitter, `rx` to REC otherwise.
    pub(super) fn inc(&mut self, tx: u16, rx: u8) {
        if self.role == Role::Tx {
            self.add_tec(tx)
        } else {
            self.add_rec(rx)
        }
    }

    pub(super) fn bus_off(&self) -> bool {
        matches!(self.mode, Mode::BusOff { .. })
    }

}
