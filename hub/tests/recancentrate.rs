//! Two complete hubs joined by two interlinks (ReCANcentrate, hub.md §1, §5.7): every
//! node has one controller per hub; only its tx controller transmits, the other one
//! receives and acknowledges. The two hubs must broadcast the same bit, blame nobody
//! in fault-free traffic, and isolate only the faulty sublink (A4).
#![allow(clippy::needless_range_loop)]
mod common;
use canstar_hdl::drive;
use canstar_hub::config::HubConfig;
use canstar_hub::top::Hub;
use common::*;

/// A closure that may corrupt the wire from one hub's `hub_tx[j]` to the other's
/// `reh_rx[j]`: (bit, wire index j, towards hub A?, value) -> value.
type WireFault = Box<dyn FnMut(usize, usize, bool, bool) -> bool>;

struct Pair {
    a: Hub,
    b: Hub,
    tracker: Tracker,
    /// nodes[k] = (controller on hub A, controller on hub B)
    nodes: Vec<(Node, Node)>,
    wire: WireFault,
    bit: usize,
    disagreements: usize,
    blames: usize,
    errors: usize,
    frames_ok: usize,
}

impl Pair {
    fn new(nodes: Vec<(Node, Node)>) -> Pair {
        let cfg = HubConfig::default();
        let mut a = Hub::new(&cfg);
        let mut b = Hub::new(&cfg);
        for h in [&mut a, &mut b] {
            for r in h.rx.iter_mut().chain(h.reh_rx.iter_mut()) {
                r.next = true;
            }
            reset_hub(h);
        }
        Pair { a, b, tracker: Tracker::default(), nodes, wire: Box::new(|_, _, _, v| v), bit: 0, disagreements: 0, blames: 0, errors: 0, frames_ok: 0 }
    }

    fn step(&mut self) {
        let n = self.nodes.len();
        // Receivers synchronise to the edges they see: a receiver's bit starts when the
        // transmitter's edge reaches its downlink (3 clocks through its own hub, 6
        // through both hubs); the transmitter's own bits start at clock 0.
        let tx_on_a = self.nodes.iter().any(|(a, _)| a.transmitting());
        let tx_on_b = self.nodes.iter().any(|(_, b)| b.transmitting());
        let lat = HubConfig::default().coupling_latency();
        let delay = |own_side_tx: bool, other_side_tx: bool, me_tx: bool| -> usize {
            if me_tx || (!own_side_tx && !other_side_tx) {
                0
            } else if own_side_tx {
                lat
            } else {
                2 * lat
            }
        };
        let mut new = vec![(true, true); n];
        let mut d = vec![(0usize, 0usize); n];
        for i in 0..n {
            let (ta, tb) = (self.nodes[i].0.transmitting(), self.nodes[i].1.transmitting());
            new[i] = (self.nodes[i].0.contribution(&self.tracker), self.nodes[i].1.contribution(&self.tracker));
            d[i] = (delay(tx_on_a, tx_on_b, ta), delay(tx_on_b, tx_on_a, tb));
        }
        let mut views = vec![(true, true); n];
        let mut rec = None;
        for k in 0..CLOCKS_PER_BIT {
            for i in 0..n {
                if k == d[i].0 {
                    self.a.rx[i].next = new[i].0;
                }
                if k == d[i].1 {
                    self.b.rx[i].next = new[i].1;
                }
            }
            for j in 0..2 {
                let to_a = self.b.hub_tx[j].val();
                let to_b = self.a.hub_tx[j].val();
                self.a.reh_rx[j].next = (self.wire)(self.bit, j, true, to_a);
                self.b.reh_rx[j].next = (self.wire)(self.bit, j, false, to_b);
            }
            drive::settle(&mut self.a);
            drive::settle(&mut self.b);
            if k == SAMPLE_CLOCK {
                let bta = self.a.core().bt.val();
                let btb = self.b.core().bt.val();
                if bta != btb {
                    self.disagreements += 1;
                }
                for (i, v) in views.iter_mut().enumerate() {
                    *v = (self.a.tx[i].val(), self.b.tx[i].val());
                }
                let (field, _) = self.tracker.classify(bta);
                let ev = self.tracker.push(bta);
                rec = Some((field, ev));
            }
            if self.a.core().blame_any() || self.b.core().blame_any() {
                self.blames += 1;
            }
            drive::cycle(&mut self.a);
            drive::cycle(&mut self.b);
        }
        let (field, ev) = rec.unwrap();
        self.errors += ev.error as usize;
        self.frames_ok += ev.frame_ok as usize;
        for i in 0..n {
            self.nodes[i].0.after(views[i].0, field, ev, &self.tracker);
            self.nodes[i].1.after(views[i].1, field, ev, &self.tracker);
        }
        self.bit += 1;
    }

    fn run_until_idle(&mut self, max: usize) {
        for _ in 0..max {
            self.step();
            if self.nodes.iter().all(|(a, b)| a.queue.is_empty() && b.queue.is_empty()) {
                for _ in 0..20 {
                    self.step();
                }
                return;
            }
        }
        panic!("did not drain");
    }

    fn sub_isolated(&self) -> (Vec<bool>, Vec<bool>) {
        (self.a.sub_isolated.iter().map(|s| s.val()).collect(), self.b.sub_isolated.iter().map(|s| s.val()).collect())
    }
    fn any_port_isolated(&self) -> bool {
        self.a.isolated.iter().chain(self.b.isolated.iter()).any(|s| s.val())
    }
}

/// Node k transmits through hub A (k = 0, 1) or hub B (k = 2).
fn system(frames: usize) -> Pair {
    let mut nodes: Vec<(Node, Node)> = (0..3).map(|_| (Node::default(), Node::default())).collect();
    for f in 0..frames {
        let k = f % 3;
        let frame = Frame::std(0x100 + 3 * f as u32, &[f as u8, 0x3c]);
        if k < 2 {
            nodes[k].0.queue.push_back(frame);
        } else {
            nodes[k].1.queue.push_back(frame);
        }
    }
    let mut p = Pair::new(nodes);
    // let both monitors integrate before the traffic starts
    let queues: Vec<_> = p.nodes.iter_mut().map(|(a, b)| (std::mem::take(&mut a.queue), std::mem::take(&mut b.queue))).collect();
    for _ in 0..14 {
        p.step();
    }
    for ((a, b), (qa, qb)) in p.nodes.iter_mut().zip(queues) {
        a.queue = qa;
        b.queue = qb;
    }
    p
}

#[test]
fn two_hubs_broadcast_the_same_bit_and_blame_nobody() {
    let mut p = system(24);
    p.run_until_idle(20_000);
    assert_eq!(p.disagreements, 0, "the two hubs' BT differ");
    assert_eq!(p.errors, 0);
    assert_eq!(p.blames, 0);
    assert_eq!(p.frames_ok, 24);
    assert_eq!(p.sub_isolated(), (vec![false, false], vec![false, false]));
    assert!(!p.any_port_isolated());
}

/// One wire of one interlink stuck at dominant / recessive / inverted, towards hub A:
/// hub A isolates exactly that incoming sublink, hub B nothing, no port is isolated
/// and every frame is delivered.
#[test]
fn faulty_sublink_isolated_only_by_the_receiving_hub() {
    for fault in 0..3 {
        let mut p = system(24);
        let start = p.bit + 100;
        p.wire = Box::new(move |b, j, to_a, v| {
            if to_a && j == 1 && b >= start {
                match fault {
                    0 => false,
                    1 => true,
                    _ => !v,
                }
            } else {
                v
            }
        });
        p.run_until_idle(60_000);
        assert_eq!(p.sub_isolated(), (vec![false, true], vec![false, false]), "fault {fault}");
        assert!(!p.any_port_isolated(), "fault {fault}");
        let sent: usize = p.nodes.iter().map(|(a, b)| a.sent + b.sent).sum();
        assert_eq!(sent, 24, "fault {fault}");
    }
}
