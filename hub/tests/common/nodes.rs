//! Simple CAN node models for the hub tests (can-protocol.md): arbitration, ACK,
//! error and overload flags from the common view of the tracker.

use super::*;

/// Behaviour of a node model.
#[derive(Clone, Debug, Default)]
pub struct NodeCfg {
    /// Never acknowledges (dead receive path towards the hub, or a deaf node).
    pub no_ack: bool,
    /// Starts its SOF in the third intermission bit (a node with a fast clock).
    pub early_sof: bool,
    /// Drives its uplink dominant at the last EOF bit of the next frame it sees.
    pub dominant_eof7_once: bool,
    /// Sends an overload flag from the first intermission bit of the next frame it sees,
    /// as a node that saw its own last EOF bit dominant (a disturbance on its downlink).
    pub overload_flag_once: bool,
}

/// A simple CAN node: transmits queued frames, arbitrates, acknowledges, sends error
/// and overload flags when the common view (tracker) or its own bit check says so.
#[derive(Clone, Debug, Default)]
pub struct Node {
    pub cfg: NodeCfg,
    pub queue: std::collections::VecDeque<Frame>,
    tx: Option<(Vec<bool>, usize)>,
    flag_left: u8,
    pub sent: usize,
    pub errors_seen: usize,
    /// Transmit error counter (only what the flag model needs).
    pub tec: u32,
    last_sent: bool,
}

impl Node {
    pub fn new(cfg: NodeCfg) -> Node {
        Node { cfg, ..Default::default() }
    }
    /// The node is transmitting (or about to, in its current frame).
    pub fn transmitting(&self) -> bool {
        self.tx.is_some()
    }
    /// Contribution for the next bit, given the tracker state before it.
    pub fn contribution(&mut self, t: &Tracker) -> bool {
        let v = self.pick(t);
        self.last_sent = v;
        v
    }
    fn pick(&mut self, t: &Tracker) -> bool {
        if self.flag_left > 0 {
            return self.tec >= 128; // passive error flag is recessive
        }
        if let Some((bits, k)) = &self.tx {
            return bits.get(*k).copied().unwrap_or(true);
        }
        match t.ph {
            Ph::Idle => {
                if let Some(f) = self.queue.front() {
                    let bits = f.wire_bits();
                    self.tx = Some((bits, 0));
                    return false;
                }
                true
            }
            Ph::Im(2) if self.cfg.early_sof && !self.queue.is_empty() => {
                let bits = self.queue.front().unwrap().wire_bits();
                self.tx = Some((bits, 0));
                false
            }
            Ph::AckSlot => !(t.crc_ok && !self.cfg.no_ack),
            Ph::Eof(6) if self.cfg.dominant_eof7_once => {
                self.cfg.dominant_eof7_once = false;
                false
            }
            Ph::Im(0) if self.cfg.overload_flag_once => {
                self.cfg.overload_flag_once = false;
                self.flag_left = 6;
                false
            }
            _ => true,
        }
    }
    /// After the bit: `view` is what the node read on its downlink, `field` the
    /// tracker's field for that bit, `ev` the tracker's event, `t` the tracker after it.
    pub fn after(&mut self, view: bool, field: Field, ev: Event, t: &Tracker) {
        if self.flag_left > 0 {
            self.flag_left -= 1;
            if self.tec < 128 && view && !self.last_sent {
                // bit error in its own active error flag: restart it
                self.tec += 8;
                self.flag_left = 6;
            }
            return;
        }
        if ev.error || ev.overload {
            if self.tx.is_some() {
                if let Some(f) = self.queue.front_mut() {
                    f.corrupt_crc = false;
                }
            }
            self.tx = None;
            self.flag_left = 6;
            if ev.error {
                self.errors_seen += 1;
            }
            return;
        }
        if let Some((bits, k)) = &mut self.tx {
            // A late joiner that treated a dominant IM3 as SOF skips its own SOF.
            if *k == 0 && field == Field::Sof {
                *k = 1;
            } else {
                let sent = bits[*k];
                let in_ack = field == Field::AckSlot;
                if in_ack && view {
                    // ACK error: the error flag starts at the ACK delimiter
                    if let Some(f) = self.queue.front_mut() {
                        f.corrupt_crc = false;
                    }
                    self.tx = None;
                    self.tec += 8;
                    self.flag_left = 6;
                    return;
                }
                if sent != view && !in_ack {
                    if sent && !view && matches!(field, Field::Id | Field::Rtr) {
                        self.tx = None; // lost arbitration
                        return;
                    }
                    self.tx = None;
                    self.tec += 8;
                    self.flag_left = 6;
                    return;
                }
                *k += 1;
                if ev.frame_ok {
                    self.queue.pop_front();
                    self.tx = None;
                    self.sent += 1;
                    self.tec = self.tec.saturating_sub(1);
                }
            }
        } else if field == Field::Sof && !self.queue.is_empty() && matches!(t.ph, Ph::Frame) {
            // Late joiner: pending frame, saw a dominant bit as SOF: start at the first ID bit.
            let bits = self.queue.front().unwrap().wire_bits();
            self.tx = Some((bits, 1));
        }
    }
}


