//! Test applications (recancentrate.md §3): 3BitCounter and Blinker send an
//! incrementing 1-byte counter under their own identifier as fast as they can;
//! every node classifies the counters it receives per sender (the Receiver
//! node's classification is the published check).

use std::collections::BTreeMap;

use canstar_controller::frame::Frame;

/// How a received counter relates to the previous one from the same sender.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Class {
    Next,
    SingleMiss,
    MultipleMiss,
    Duplicate,
}

/// A sender: the next counter value to send.
#[derive(Clone, Debug)]
pub struct Sender {
    pub id: u32,
    pub next: u8,
    /// Frames reported sent.
    pub sent: u64,
}

impl Sender {
    pub fn new(id: u32) -> Self {
        Sender { id, next: 0, sent: 0 }
    }
    /// The frame to send now.
    pub fn frame(&self) -> Frame {
        Frame::std(self.id, &[self.next])
    }
    /// The driver reported the frame sent: move on.
    pub fn success(&mut self) {
        self.next = self.next.wrapping_add(1);
        self.sent += 1;
    }
}

/// Per-sender classification of received counters. The first value expected
/// from every sender is 0.
#[derive(Clone, Debug, Default)]
pub struct Receiver {
    last: BTreeMap<u32, u8>,
    pub next: u64,
    pub single_miss: u64,
    pub multiple_miss: u64,
    pub duplicates: u64,
    /// (sender id, first missed value, last missed value).
    pub misses: Vec<(u32, u8, u8)>,
    /// After [`Receiver::rejoin`]: the next value of every sender is taken as it comes.
    rejoined: bool,
}

impl Receiver {
    /// The node was switched off and on again: what it missed while off is no loss, so
    /// the first value of each sender after this call starts a new sequence.
    pub fn rejoin(&mut self) {
        self.rejoined = true;
        self.last.clear();
    }

    /// Classify a delivered frame (frames without data are ignored).
    pub fn deliver(&mut self, f: &Frame) -> Option<Class> {
        let v = *f.data.first()?;
        if self.rejoined && !self.last.contains_key(&f.id) {
            self.last.insert(f.id, v);
            self.next += 1;
            return Some(Class::Next);
        }
        let last = self.last.get(&f.id).copied().unwrap_or(255);
        let class = if v == last.wrapping_add(1) {
            Class::Next
        } else if v == last {
            Class::Duplicate
        } else if v == last.wrapping_add(2) {
            Class::SingleMiss
        } else {
            Class::MultipleMiss
        };
        match class {
            Class::Next => self.next += 1,
            Class::Duplicate => self.duplicates += 1,
            Class::SingleMiss => self.single_miss += 1,
            Class::MultipleMiss => self.multiple_miss += 1,
        }
        if matches!(class, Class::SingleMiss | Class::MultipleMiss) {
            self.misses.push((f.id, last.wrapping_add(1), v.wrapping_sub(1)));
        }
        if class != Class::Duplicate {
            self.last.insert(f.id, v);
        }
        Some(class)
    }
    /// Last value received from `id`.
    pub fn last(&self, id: u32) -> Option<u8> {
        self.last.get(&id).copied()
    }
}
